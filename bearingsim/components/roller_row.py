"""Quasi-static row of Z cylindrical rollers between an inner and an outer ring frame (NU type).

Each roller is cut into ``ns`` slices along its effective length ``Lwe`` (slice ``k`` at the
axial position ``z_k = (k + 1/2) Lwe/ns - Lwe/2`` from the row's centre plane). With rigid rings
in small-rotation kinematics (the form of ISO/TS 16281 and of Harris & Kotzalas, *Advanced
Concepts*, chapter "Distribution of internal loading", misaligned cylindrical roller bearings),
the inner raceway approaches the outer one at roller ``j`` (azimuth ``psi_j = psi0 + 2 pi j/Z``)
and slice ``k`` by

    delta_jk = (x + z_k ty) cos psi_j + (y - z_k tx) sin psi_j - Pd/2

with ``(x, y, tx, ty)`` the inner ring's displacement and tilt relative to the outer ring and
``Pd`` the diametral clearance. Palmgren's line contact law is the same at both raceways, so a
free roller (it may shift and tilt in its azimuth plane) takes half of ``delta_jk`` at each
contact, and slice ``k`` carries ``q_jk = Q(delta_jk / 2) / ns``
(:class:`~bearingsim.components.rolling_element.LineContact`): every roller is in equilibrium
without unknowns of its own. A tilt (misalignment) loads the slices of a roller unevenly, up to
edge loading of the straight roller (no crowning is modelled).

The rollers put ``-q_jk e_r`` on the inner ring at ``(dm/2 e_r, z_k)`` (moments ``z_k q_jk
sin psi_j`` about x and ``-z_k q_jk cos psi_j`` about y) and the opposite on the outer ring;
the inner ring slides on the rollers axially (NU: no ribs), so the row carries no axial
force. The slice loads' sum is the roller load ``Q_j``; the largest slice load gives the
maximum Hertz pressure at the inner contact, ``p_max = sqrt(q_max/w E' / (2 pi R_i))``
(:func:`~bearingsim.physics.line_contact.max_pressure`, ``w = Lwe/ns``, ``R_i = Dw (dm - Dw) /
(2 dm)``), the larger of the two contacts' pressures.

Loads and geometry in SI; floats and CasADi SX alike (:func:`roller_row_loads`).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from bearingsim import symbolic as op
from bearingsim.catalog.rollers import RollerBearingGeometry, resolve_roller_bearing
from bearingsim.components.connectors import RingFrame
from bearingsim.components.rolling_element import LineContact
from bearingsim.language import Component, Parameter, Variable
from bearingsim.physics.materials import STEEL, Material, effective_modulus
from bearingsim.physics.ring_equilibrium import EquilibriumProblem
from bearingsim.validation import check_count, check_range

__all__ = [
    "RollerRow",
    "RollerRowParameters",
    "RollerContacts",
    "RollerEquilibrium",
    "roller_row_parameters",
    "roller_row_loads",
    "roller_row_stiffness",
    "roller_row_equilibrium",
    "roller_row_lives",
    "slice_positions",
]


@dataclass(frozen=True)
class RollerRowParameters:
    """Numeric parameters of a roller row (SI); the component's parameters have these names.

    Attributes
    ----------
    Dw, dm, Lwe : roller diameter, pitch diameter, effective roller length [m]
    Pd : diametral clearance [m]
    E_eff : effective modulus ``E'`` of roller and ring [Pa]
    psi0 : azimuth of roller 0 [rad]
    smooth : regularization length of the contact law [m]; None: the exact ``max(delta, 0)``
        (numeric evaluation only, not differentiable at first contact)
    """

    Dw: float
    dm: float
    Lwe: float
    Pd: float
    E_eff: float
    psi0: float = 0.0
    smooth: float | None = 1e-9


def roller_row_parameters(bearing: str | RollerBearingGeometry, clearance: float | None = None,
                          roller_position_angle: float = 0.0, smooth: float = 1e-9,
                          roller: Material = STEEL, ring: Material = STEEL
                          ) -> RollerRowParameters:
    """Row parameters of a catalogue roller bearing.

    Parameters
    ----------
    bearing : str or RollerBearingGeometry
    clearance : float, optional
        Diametral clearance Pd [m], >= 0 (default: the catalogue's).
    roller_position_angle : float
        Azimuth of roller 0 [rad].
    smooth : float
        Regularization length [m], > 0.
    roller, ring : Material

    Returns
    -------
    RollerRowParameters
    """
    g = resolve_roller_bearing(bearing)
    where = f"roller_row_parameters({g.designation})"
    pd = g.diametral_clearance if clearance is None else clearance
    check_range(pd, "clearance", "m", 0.0, 0.1 * g.roller_diameter, where=where)
    check_range(roller_position_angle, "roller_position_angle", "rad", where=where)
    check_range(smooth, "smooth", "m", 0.0, low_inclusive=False, where=where)
    return RollerRowParameters(g.roller_diameter, g.pitch_diameter, g.roller_length, float(pd),
                               effective_modulus(roller, ring), float(roller_position_angle),
                               float(smooth))


@dataclass
class RollerContacts:
    """Results of :func:`roller_row_loads` (floats or SX).

    Attributes
    ----------
    q : list of Z lists of ns
        Slice loads [N] of every roller.
    Q : list of Z
        Roller loads [N].
    delta : list of Z
        Total approach of each roller at its centre plane [m] (negative: a gap).
    p_max : list of Z
        Maximum Hertz pressure of each roller (inner contact, most loaded slice) [Pa].
    inner_load, outer_load : list of 5
        (Fx, Fy, Fz, Mx, My) the rollers put on the inner and outer ring [N, N m].
    """

    q: list
    Q: list
    delta: list
    p_max: list
    inner_load: list
    outer_load: list


def slice_positions(length: float, n_slices: int) -> list[float]:
    """Axial positions of the slice centres from the row's centre plane [m].

    Parameters
    ----------
    length : float
        Effective roller length [m].
    n_slices : int

    Returns
    -------
    list of float
    """
    check_count(n_slices, "n_slices", 1, where="slice_positions")
    width = length / n_slices
    return [(k + 0.5) * width - 0.5 * length for k in range(n_slices)]


def roller_row_loads(p: Any, inner, outer, n_rollers: int, n_slices: int) -> RollerContacts:
    """Slice and roller loads of a roller row and the loads it puts on its rings.

    Parameters
    ----------
    p : RollerRowParameters or RollerRow
        Anything with the attributes of :class:`RollerRowParameters`.
    inner, outer : sequence of 5
        Displacements (x, y, z, tx, ty) of the inner and outer ring frames [m, rad].
    n_rollers : int
        Z.
    n_slices : int
        Slices per roller.

    Returns
    -------
    RollerContacts
    """
    law = LineContact(p.Lwe, n_slices)
    x, y = inner[0] - outer[0], inner[1] - outer[1]
    tx, ty = inner[3] - outer[3], inner[4] - outer[4]
    width = p.Lwe / n_slices
    positions = slice_positions(p.Lwe, n_slices)
    radius = p.Dw * (p.dm - p.Dw) / (2.0 * p.dm)
    out = RollerContacts([], [], [], [], [0.0] * 5, [0.0] * 5)
    for j in range(n_rollers):
        psi = p.psi0 + 2.0 * math.pi * j / n_rollers
        c, s = op.cos(psi), op.sin(psi)
        approaches = [(x + z * ty) * c + (y - z * tx) * s - 0.5 * p.Pd for z in positions]
        q = law.slice_loads(approaches, p.smooth)
        total = sum(q)
        q_max = q[0]
        for v in q[1:]:
            q_max = op.fmax(q_max, v)
        out.q.append(q)
        out.Q.append(total)
        out.delta.append((x * c + y * s) - 0.5 * p.Pd)
        out.p_max.append(op.sqrt(q_max * p.E_eff / (2.0 * math.pi * width * radius)))
        moment_x = sum(z * v for z, v in zip(positions, q, strict=True)) * s
        moment_y = -sum(z * v for z, v in zip(positions, q, strict=True)) * c
        on_inner = [-total * c, -total * s, 0.0, moment_x, moment_y]
        out.inner_load = [a + b for a, b in zip(out.inner_load, on_inner, strict=True)]
    out.outer_load = [-v for v in out.inner_load]
    return out


class RollerRow(Component):
    """Quasi-static row of Z cylindrical rollers (sliced line contacts) between an inner-ring
    and an outer-ring frame; the module docstring gives the equations.

    Parameters
    ----------
    bearing : str or RollerBearingGeometry
        Catalogue designation (e.g. "NU206") or geometry.
    n_slices : int
        Slices per roller (>= 1; one slice cannot resolve a tilt).
    clearance : float, optional
        Diametral clearance Pd [m] (default: the catalogue's).
    roller_position_angle : float
        Azimuth of roller 0 [rad].
    smooth : float
        Contact regularization length [m].
    roller, ring : Material
    name : str
        Instance name (the prefix of its variables' dotted names).

    Parameters (model)
    ------------------
    Dw, dm, Lwe, Pd [m]; E_eff [Pa]; psi0 [rad]; smooth [m].

    Variables
    ---------
    Q[j] [N] : load of roller j
    delta[j] [m] : approach of roller j at its centre plane (negative: clearance)
    p_max[j] [Pa] : maximum contact pressure of roller j

    Connectors
    ----------
    inner, outer : RingFrame (flows: loads of the rings on the row)
    """

    def __init__(self, bearing: str | RollerBearingGeometry = "NU206", n_slices: int = 10, *,
                 clearance: float | None = None, roller_position_angle: float = 0.0,
                 smooth: float = 1e-9, roller: Material = STEEL, ring: Material = STEEL,
                 name=None):
        super().__init__(name)
        self.geometry = resolve_roller_bearing(bearing)
        check_count(n_slices, "n_slices", 1, where=self.display_name)
        self.n_slices = int(n_slices)
        self.n_rollers = self.geometry.roller_count
        rp = roller_row_parameters(self.geometry, clearance, roller_position_angle, smooth,
                                   roller, ring)
        pos = {"low": 0.0, "low_inclusive": False}
        self.Dw = Parameter(rp.Dw, "m", "roller diameter", **pos)
        self.dm = Parameter(rp.dm, "m", "pitch diameter", **pos)
        self.Lwe = Parameter(rp.Lwe, "m", "effective roller length", **pos)
        self.Pd = Parameter(rp.Pd, "m", "diametral clearance", low=0.0)
        self.E_eff = Parameter(rp.E_eff, "Pa", "effective modulus of roller and ring", **pos)
        self.psi0 = Parameter(rp.psi0, "rad", "roller position angle (azimuth of roller 0)")
        self.smooth = Parameter(rp.smooth, "m", "contact regularization length", **pos)
        self.inner = RingFrame()
        self.outer = RingFrame()
        labels = (("Q", "N", "roller load"), ("delta", "m", "roller approach at its centre"),
                  ("p_max", "Pa", "maximum contact pressure of the roller"))
        self._outputs = {key: [self.add(f"{key}[{j}]", Variable(unit=unit, description=text))
                               for j in range(self.n_rollers)] for key, unit, text in labels}

    def output_names(self, key: str) -> list[str]:
        """Dotted names of the per-roller variable ``key`` ("Q", "delta", "p_max").

        Parameters
        ----------
        key : str
            A per-roller variable ("Q", "delta", "p_max").

        Returns
        -------
        list of str
            Its dotted names, one per roller.
        """
        return [f"{self.path}.{key}[{j}]" for j in range(self.n_rollers)]

    def loads(self) -> RollerContacts:
        """:func:`roller_row_loads` on this row's symbols.

        Returns
        -------
        RollerContacts
            Slice and roller loads of every roller (symbols).
        """
        return roller_row_loads(self, self.inner.displacement(), self.outer.displacement(),
                                self.n_rollers, self.n_slices)

    def equations(self):
        c = self.loads()
        eqs = [var == val for key, values in self._outputs.items()
               for var, val in zip(values, getattr(c, key), strict=True)]
        eqs += [f == -load for f, load in zip(self.inner.loads(), c.inner_load, strict=True)]
        eqs += [f == -load for f, load in zip(self.outer.loads(), c.outer_load, strict=True)]
        return eqs


@functools.lru_cache(maxsize=32)
def _row_function(p: RollerRowParameters, n_rollers: int, n_slices: int) -> ca.Function:
    """:func:`roller_row_loads` of the inner ring's displacement (outer ring fixed) as one
    CasADi function, built once per row (a statics sweep's points share it; building the
    row's expressions is most of a solve): ``q5 -> (inner_load, Q, delta, p_max, q (Z x ns,
    row by row), d inner_load / d q5)``."""
    q = ca.SX.sym("q", 5)
    c = roller_row_loads(p, [q[k] for k in range(5)], [0.0] * 5, n_rollers, n_slices)
    load = ca.vertcat(*c.inner_load)
    return ca.Function("roller_row", [q], [load, ca.vertcat(*c.Q), ca.vertcat(*c.delta),
                                           ca.vertcat(*c.p_max),
                                           ca.vertcat(*[v for r in c.q for v in r]),
                                           ca.jacobian(load, q)])


def _numeric_contacts(p: RollerRowParameters, n_rollers: int, n_slices: int,
                      inner) -> tuple[RollerContacts, np.ndarray]:
    """:func:`roller_row_loads` at a numeric displacement of the inner ring (outer ring
    fixed), in floats, and the Jacobian of its load on the inner ring."""
    out = [np.asarray(v.full(), dtype=float).ravel()
           for v in _row_function(p, n_rollers, n_slices)(ca.DM([float(v) for v in inner]))]
    load, jacobian = out[0].tolist(), out[5].reshape(5, 5)
    slices = out[4].reshape(n_rollers, n_slices).tolist()
    return RollerContacts(slices, out[1].tolist(), out[2].tolist(), out[3].tolist(), load,
                          [-v for v in load]), jacobian


def roller_row_stiffness(p: RollerRowParameters, n_rollers: int, n_slices: int,
                         inner=(0.0,) * 5) -> np.ndarray:
    """5x5 stiffness of a roller row from the exact CasADi Jacobian.

    ``K = -d(load on the inner ring) / d(inner ring displacement)``, outer ring fixed, ordered
    (x, y, z, tx, ty); the z row and column are 0 (NU: no axial load path).

    Parameters
    ----------
    p : RollerRowParameters
    n_rollers, n_slices : int
    inner : sequence of 5
        Inner ring displacement of the operating point [m, rad].

    Returns
    -------
    numpy.ndarray of shape (5, 5)
    """
    return -_numeric_contacts(p, n_rollers, n_slices, inner)[1]


@dataclass(frozen=True)
class RollerEquilibrium:
    """Result of :func:`roller_row_equilibrium`."""

    inner: np.ndarray
    """Inner ring displacement (x, y, z, tx, ty) against the outer ring [m, rad]."""
    contacts: RollerContacts
    """Slice and roller loads there (floats)."""
    moment: np.ndarray
    """(Mx, My) [N m] the shaft must apply to hold the imposed tilt."""
    stiffness: np.ndarray
    """5x5 stiffness of the row there (:func:`roller_row_stiffness`, from the same
    evaluation as ``contacts``)."""


def roller_row_equilibrium(p: RollerRowParameters, n_rollers: int, n_slices: int,
                           loads=(0.0, 0.0), tilt=(0.0, 0.0)) -> RollerEquilibrium:
    """Radial equilibrium of the inner ring under the radial load ``(Fx, Fy)`` at an imposed
    tilt ``(tx, ty)`` (misalignment), by Newton (Levenberg-Marquardt from a seated start on the
    exact Jacobian, :class:`~bearingsim.physics.ring_equilibrium.EquilibriumProblem`).

    Parameters
    ----------
    p : RollerRowParameters
    n_rollers, n_slices : int
    loads : (Fx, Fy)
        External radial load on the inner ring [N].
    tilt : (tx, ty)
        Inner ring tilt against the outer ring [rad].

    Returns
    -------
    RollerEquilibrium

    Raises
    ------
    SimulationError
        If no equilibrium is found.
    """
    check_range(tilt[0], "tilt[0]", "rad", -0.01, 0.01, where="roller_row_equilibrium")
    check_range(tilt[1], "tilt[1]", "rad", -0.01, 0.01, where="roller_row_equilibrium")
    v = ca.SX.sym("v", 2)
    ring = ca.vertcat(v, 0.0, float(tilt[0]), float(tilt[1]))
    load = _row_function(p, n_rollers, n_slices)(ring)[0]
    problem = EquilibriumProblem(ca.Function("roller_row", [v], [load[:2]]),
                                 2, [1e-5, 1e-5], [1.0, 1.0],
                                 name=f"roller_row_equilibrium({n_rollers} rollers)")
    xy = problem.solve(np.asarray(loads, dtype=float))
    inner = np.array([xy[0], xy[1], 0.0, float(tilt[0]), float(tilt[1])])
    numeric, jacobian = _numeric_contacts(p, n_rollers, n_slices, inner)
    moment = -np.array(numeric.inner_load[3:5])
    return RollerEquilibrium(inner, numeric, moment, -jacobian)


def roller_row_lives(bearing: str | RollerBearingGeometry, clearance: float | None, positions,
                     n_slices: int) -> np.ndarray:
    """ISO/TS 16281 roller-form reference rating life L10r [10^6 rev] of a catalogue bearing's
    row at each position of its inner ring (rotating) against the outer ring, from the slice
    loads of the exact contact law (unloaded slices carry nothing: a bearing without load has
    an infinite life, not the huge one of the regularized slices' tiny loads).

    Parameters
    ----------
    bearing : str or RollerBearingGeometry
        Designation or geometry.
    clearance : float or None
        Diametral clearance [m] (None: the catalogue's).
    positions : sequence of sequences of 5
        Inner ring displacements (x, y, z, tx, ty) [m, rad].
    n_slices : int
        Slices per roller.

    Returns
    -------
    numpy.ndarray
        L10r [10^6 revolutions] at each position (inf without load).
    """
    from bearingsim.physics.life import roller_reference_rating_life

    g = resolve_roller_bearing(bearing)
    exact = dataclasses.replace(roller_row_parameters(g, clearance), smooth=None)
    lives = []
    for inner in positions:
        q = _numeric_contacts(exact, g.roller_count, n_slices, inner)[0].q
        lives.append(float(roller_reference_rating_life(q, q, g.dynamic_load_rating, g.gamma)))
    return np.asarray(lives)
