"""The ball row as a component between an inner and an outer ring frame (:class:`BallRow`)."""

from __future__ import annotations

import numpy as np

from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.ball_row.loads import BallContacts, row_loads
from bearingsim.components.ball_row.parameters import (
    _MAX_ALPHA,
    REFERENCES,
    STEEL_DENSITY,
    row_parameters,
)
from bearingsim.components.connectors import RingFrame
from bearingsim.errors import ParameterError
from bearingsim.language import Component, Parameter, Variable
from bearingsim.physics.materials import STEEL, Material
from bearingsim.validation import check_choice, check_range


class BallRow(Component):
    """Quasi-static row of Z balls between an inner-ring and an outer-ring frame.

    Parameters
    ----------
    bearing : str or BearingGeometry
        Catalogue designation or geometry (Dw, dm, fi, fo, Z, free contact angle).
    direction : {1, -1}
        Axial direction s of the row: the row is loaded when the inner ring moves along s z
        relative to the outer ring.
    contact_angle : float, optional
        Free contact angle a0 [rad] in [0, 45 deg] (default: the bearing's free contact angle;
        for a deep-groove bearing the one its radial clearance gives).
    ball_position_angle : float
        Azimuth psi0 of ball 0 from the x axis [rad].
    speed_effects : bool
        Jones-Harris form with centrifugal force and gyroscopic moment (two unknowns per ball)
        instead of the classic explicit form.
    reference : {"touching", "centred"}
        Reference configuration: balls just touching at a0 (angular contact rows), or the rings
        centred with the radial clearance (deep-groove rows).
    exact : bool
        Exact rigid-ring kinematics (default) or the small-angle form.
    smooth : float
        Regularization length of the contact law [m] (module docstring).
    ball, ring : Material
        Materials for the Hertz constants.
    ball_density : float
        Ball density [kg/m^3] (centrifugal force, gyroscopic moment).
    representative : bool
        Axisymmetric reduction for a pure axial load: ball 0 is solved alone under the axial
        displacement of the rings and stands for every ball (all per-ball outputs equal it);
        the row transmits ``Z`` times its axial load and no radial force or moment. Valid only
        while the rings do not move radially or tilt, which a pure axial load on a symmetric
        assembly guarantees.
    centre_start : sequence of (float, float), optional
        Jones-Harris form: start values (Newton guesses) of every ball's ``(b_r, b_z)`` [m],
        e.g. from :func:`row_equilibrium`; default 0 (the pitch circle).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Parameters (model)
    ------------------
    Dw, dm [m]; fi, fo [-]; alpha0 [rad]; K_i, K_o [N/m^1.5]; psi0 [rad]; smooth [m];
    inner_speed, outer_speed [rad/s]; ball_density [kg/m^3].

    Variables
    ---------
    Q_i[j], Q_o[j] [N] : inner and outer contact loads of ball j
    alpha_i[j], alpha_o[j] [rad] : operating contact angles
    delta[j] [m] : total elastic approach of ball j (negative: clearance)
    b_r[j], b_z[j] [m] : ball centre offsets (Jones-Harris form only)

    Connectors
    ----------
    inner, outer : RingFrame (flows: loads of the rings on the row)
    """

    def __init__(self, bearing: str | BearingGeometry = "7020C", direction: int = 1, *,
                 contact_angle: float | None = None, ball_position_angle: float = 0.0,
                 speed_effects: bool = False, reference: str = "touching", exact: bool = True,
                 smooth: float = 1e-9, ball: Material = STEEL, ring: Material = STEEL,
                 ball_density: float = STEEL_DENSITY, representative: bool = False,
                 centre_start=None, name=None):
        super().__init__(name)
        self.geometry = resolve_bearing(bearing)
        self.representative = bool(representative)
        check_choice(direction, "direction", (1, -1), self.display_name)
        if reference not in REFERENCES:
            raise ParameterError(f"{self.display_name}: reference must be one of {REFERENCES}, "
                                 f"got {reference!r}")
        where = f"{type(self).__name__}({self.geometry.designation})"
        if contact_angle is not None:
            check_range(contact_angle, "contact_angle", "rad", 0.0, _MAX_ALPHA, where=where)
        rp = row_parameters(self.geometry, contact_angle, ball_position_angle, smooth, ball,
                            ring)
        self.n_balls = self.geometry.ball_count
        self.direction = direction
        self.reference = reference
        self.exact = exact
        self.speed_effects = speed_effects
        pos = {"low": 0.0, "low_inclusive": False}
        self.Dw = Parameter(rp.Dw, "m", "ball diameter", **pos)
        self.dm = Parameter(rp.dm, "m", "pitch diameter", **pos)
        self.fi = Parameter(rp.fi, "1", "inner groove curvature factor", low=0.5, high=1.0,
                            low_inclusive=False)
        self.fo = Parameter(rp.fo, "1", "outer groove curvature factor", low=0.5, high=1.0,
                            low_inclusive=False)
        self.alpha0 = Parameter(rp.alpha0, "rad", "free contact angle", low=0.0, high=_MAX_ALPHA)
        self.K_i = Parameter(rp.K_i, "N/m^1.5", "Hertz constant, inner contact", **pos)
        self.K_o = Parameter(rp.K_o, "N/m^1.5", "Hertz constant, outer contact", **pos)
        self.psi0 = Parameter(rp.psi0, "rad", "ball position angle (azimuth of ball 0)")
        self.smooth = Parameter(rp.smooth, "m", "contact regularization length", **pos)
        self.interference = Parameter(rp.interference, "m", "groove-centre interference of a "
                                      "preloaded deep-groove row (-Pd/2)", low=0.0)
        self.inner_speed = Parameter(0.0, "rad/s", "inner ring speed")
        self.outer_speed = Parameter(0.0, "rad/s", "outer ring speed")
        self.ball_density = Parameter(ball_density, "kg/m3", "ball density", **pos)
        self.inner = RingFrame()
        self.outer = RingFrame()
        z = self.n_balls
        labels = (("Q_i", "N", "inner contact load"), ("Q_o", "N", "outer contact load"),
                  ("alpha_i", "rad", "inner contact angle"),
                  ("alpha_o", "rad", "outer contact angle"),
                  ("delta", "m", "total elastic approach"))
        self._outputs = {key: [self.add(f"{key}[{j}]", Variable(unit=unit, description=text))
                               for j in range(z)] for key, unit, text in labels}
        self._centres = None
        if speed_effects:
            n_centres = 1 if self.representative else z
            starts = (np.zeros((n_centres, 2)) if centre_start is None
                      else np.asarray(centre_start, dtype=float).reshape(n_centres, 2))
            self._centres = [
                (self.add(f"b_r[{j}]", Variable(float(starts[j, 0]), "m",
                                                "ball centre radial offset", fixed=False)),
                 self.add(f"b_z[{j}]", Variable(float(starts[j, 1]), "m",
                                                "ball centre axial offset", fixed=False)))
                for j in range(n_centres)]

    def output_names(self, key: str) -> list[str]:
        """Dotted names of the per-ball variable ``key`` (e.g. "Q_i") in ball order.

        Parameters
        ----------
        key : str
            A per-ball variable ("Q_i", "alpha_i", ...).

        Returns
        -------
        list of str
            Its dotted names, one per ball.
        """
        return [f"{self.path}.{key}[{j}]" for j in range(self.n_balls)]

    def loads(self) -> BallContacts:
        """:func:`row_loads` on this row's symbols.

        Returns
        -------
        BallContacts
            Contact loads and angles of every ball (symbols).
        """
        return row_loads(self, self.inner.displacement(), self.outer.displacement(),
                         self.n_balls, self.direction, reference=self.reference,
                         exact=self.exact, ball_centres=self._centres,
                         speeds=(self.inner_speed, self.outer_speed),
                         ball_density=self.ball_density)

    def representative_loads(self) -> BallContacts:
        """:func:`row_loads` of ball 0 alone under the axial part of the ring displacements.

        Returns
        -------
        BallContacts
            Contact loads and angles of ball 0 (symbols).
        """
        def axial(frame):
            return [0.0, 0.0, frame.z, 0.0, 0.0]

        return row_loads(self, axial(self.inner), axial(self.outer), 1, self.direction,
                         reference=self.reference, exact=self.exact,
                         ball_centres=self._centres, speeds=(self.inner_speed, self.outer_speed),
                         ball_density=self.ball_density)

    def equations(self):
        if self.representative:
            return self._representative_equations()
        c = self.loads()
        eqs = [var == val for key, values in self._outputs.items()
               for var, val in zip(values, getattr(c, key), strict=True)]
        eqs += list(c.residual)
        # the row's connector flows are the loads of the rings on the row
        eqs += [f == -load for f, load in zip(self.inner.loads(), c.inner_load, strict=True)]
        eqs += [f == -load for f, load in zip(self.outer.loads(), c.outer_load, strict=True)]
        return eqs

    def _representative_equations(self):
        """Axisymmetric row: ball 0 stands for all balls; only the axial load is transmitted."""
        c = self.representative_loads()
        z = self.n_balls
        eqs = [var == getattr(c, key)[0] for key, values in self._outputs.items()
               for var in values]
        eqs += list(c.residual)
        for frame, load in ((self.inner, c.inner_load), (self.outer, c.outer_load)):
            fx, fy, fz, mx, my = frame.loads()
            eqs += [fz == -z * load[2], fx == 0, fy == 0, mx == 0, my == 0]
        return eqs
