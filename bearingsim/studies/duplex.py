"""Duplex pair studies (docs/studies.md, section B): equilibrium, stiffness and modes.

One assembled system serves every configuration: preload (the spacer width difference or the
DT spring force), contact angle (with the Hertz constants it implies), speed and ball position
angle are parameters of the compiled functions, so a sweep re-solves without re-assembling.
The pair's own configuration (``DuplexModel(pair_options=...)``) is the default; a study
overrides only what it is given. Sweeps over one parameter are in
:mod:`bearingsim.studies.duplex_sweep`.

* **Equilibrium**: ``dx/dt = 0`` of the assembled model (Newton with the exact Jacobian).
* **Stiffness**: the exact static compliance ``C = d q / d F_ext = -(A^-1 B)_q`` of the model
  linearized at the equilibrium (CasADi's exact Jacobians, through the Newton blocks by the
  implicit function theorem), ``K = C^-1`` about the shaft's centre of mass. This includes a
  spring-damper housing in series. No finite differences.
* **Modes**: ``K phi = w^2 M phi`` with ``M = diag(m, m, m, Jt, Jt)`` (:func:`scipy.linalg.eigh`
  on the symmetric part of K), modes named after their dominant degree of freedom. Damping
  follows the study's loss factor (docs/studies.md, section B), ``eta = 0.005``: hysteretic damping
  ``C = (eta / w) K`` at each mode's frequency, i.e. the modal damping ratio ``zeta = eta / 2``
  (Harris & Piersol, *Shock and Vibration Handbook*, chapter "Material damping").
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assemblies.duplex import (
    ARRANGEMENTS,
    DuplexOptions,
    duplex_pair,
    offset_preload,
    preload_force,
    preload_offset,
)
from bearingsim.assemblies.duplex.limits import check_pair_loads, check_pair_speed
from bearingsim.assemblies.duplex.options import si_option
from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.ball_row import axial_approach, row_parameters
from bearingsim.errors import ParameterError, PlasticDeformationWarning, SimulationError
from bearingsim.physics.shaft_modes import DOFS, LOSS_FACTOR, Modes, modal_analysis
from bearingsim.simulation import steady_state
from bearingsim.simulation.statics import static_stiffness
from bearingsim.units import engineering
from bearingsim.validation import check_mapping, keyword_names

__all__ = [
    "RowUnloadedWarning",
    "DuplexModel",
    "Equilibrium",
]

_LOADS = tuple(f"shaft.{k}" for k in ("Fx", "Fy", "Fz", "Mx", "My"))
_POSITIONS = tuple(f"shaft.{k}" for k in DOFS)
_PAIR_OPTIONS = frozenset(keyword_names(DuplexOptions, ("bearing", "arrangement"))) | {"name"}
_UNLOADED = 1e-3  # N: a row whose largest ball load is below this is reported as unloaded
_ACCEL_TOL = 1e-7  # m/s^2, rad/s^2: equilibrium residual (displacement error ~ m a / k < 1e-13)


class RowUnloadedWarning(UserWarning):
    """A ball row of the pair carries no load at the equilibrium (spacer or external load)."""


def _check_reverse_thrust(fz: float, spring: float, where: str) -> None:
    """Warn when an axial load ``fz`` [N] against a tandem pair's loaded direction exceeds its
    spring preload ``spring`` [N] (signed: its direction is the loaded one): both rows then
    carry it on the shoulders an angular contact bearing does not have in full, which the row
    model, a full groove, does not know (a 7020C DT pair took -20 kN for -0.37 mm)."""
    if fz * math.copysign(1.0, spring) < -abs(spring):
        warnings.warn(f"{where}: Fz = {fz:g} N acts against the tandem pair's loaded "
                      f"direction beyond its spring preload of {abs(spring):g} N: the rows "
                      "lose their preload and would separate (a DT pair takes axial load in "
                      "one direction; another bearing must take the reverse); the model "
                      "carries it on the rows as if their raceways had full shoulders, which "
                      "is not physical", RowUnloadedWarning, stacklevel=3)


@dataclass
class Equilibrium:
    """Quasi-static equilibrium of a duplex pair.

    Attributes
    ----------
    displacement : ndarray (5,)
        Shaft (x, y, z, tx, ty) at the centre of mass [m, rad].
    state : ndarray
        Full state vector (for :func:`~bearingsim.simulation.linearize`).
    inputs : dict
        External loads by input name [N, N m].
    parameters : dict
        Parameter overrides of the configuration.
    Q_i, Q_o : ndarray (2, Z)
        Ball loads at the inner and outer race of each row [N].
    alpha_i, alpha_o : ndarray (2, Z)
        Contact angles [rad].
    delta : ndarray (2, Z)
        Total elastic approach of each ball [m].
    spacer_force : float
        Axial force of the inner spacer on row 1's inner ring [N].
    """

    displacement: np.ndarray
    state: np.ndarray
    inputs: dict
    parameters: dict
    Q_i: np.ndarray
    Q_o: np.ndarray
    alpha_i: np.ndarray
    alpha_o: np.ndarray
    delta: np.ndarray
    spacer_force: float

    @property
    def row_axial_loads(self) -> np.ndarray:
        """Axial load carried by each row, ``sum_j Q_ij sin(alpha_ij)`` [N].

        Returns
        -------
        ndarray
            Axial load of row 0 and row 1 [N].
        """
        return np.sum(self.Q_i * np.sin(self.alpha_i), axis=1)

    def __repr__(self) -> str:
        shaft = ", ".join(f"{d} {engineering(float(v), 'rad' if d.startswith('t') else 'm')}"
                          for d, v in zip(DOFS, self.displacement, strict=True))
        rows = ", ".join(engineering(float(f), "N") for f in self.row_axial_loads)
        return (f"<Equilibrium: shaft {shaft}; row axial loads {rows}; largest ball load "
                f"{engineering(float(np.max(self.Q_i)), 'N')}; spacer force "
                f"{engineering(float(self.spacer_force), 'N')}>")


@functools.lru_cache(maxsize=256)
def _spacer_offset(geometry: BearingGeometry, force: float, arrangement: str,
                   contact_angle: float) -> float:
    """:func:`~bearingsim.assemblies.duplex.preload_offset` of one configuration, solved once
    per process [m]: its axial approach is a root search over the balls in Python (~0.1 s),
    and every equilibrium, mode set and sweep point of a configuration asks for it again."""
    return preload_offset(geometry, force, arrangement, contact_angle)


@dataclass
class DuplexModel:  # numpydoc ignore=PR02
    """An assembled duplex pair and the parameter values of its configurations.

    Parameters
    ----------
    bearing : str or BearingGeometry
        Bearing of the rows. Bearings that differ only in contact angle and preload classes
        (7020C, 7020A5, 7020A) share one model: pass them to :meth:`parameters`.
    arrangement : {"DF", "DB", "DT"}
    pair_options : dict
        Further fields of :class:`~bearingsim.assemblies.duplex.DuplexOptions` and ``name``
        (shaft, speed_effects, housing_stiffness, exact, smooth, ...). The configuration
        options ``preload`` [N or class], ``speed`` [rad/s], ``contact_angle`` [rad],
        ``ball_position_angle`` [rad] and ``spacer_offset`` [m] become the model's default
        configuration: :meth:`parameters`, :meth:`equilibrium`, :meth:`modes` and
        :func:`~bearingsim.studies.duplex_sweep.sweep` use them unless given explicitly.
        ``axisymmetric`` is rejected (the studies need the radial and tilt load paths), and so
        are ``bearing``, ``arrangement`` and unknown names.

    Raises
    ------
    ParameterError
        For a pair option that the studies cannot honour or that the pair does not take.
    """

    bearing: str | BearingGeometry = "7020C"
    arrangement: str = "DF"
    pair_options: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        options = check_mapping(self.pair_options, "pair_options", "DuplexModel",
                                "DuplexPair option names")
        bad = sorted(set(options) & {"bearing", "arrangement"})
        if bad:
            raise ParameterError(f"DuplexModel: give {', '.join(bad)} as DuplexModel's own "
                                 "argument, not in pair_options")
        unknown = sorted(set(options) - _PAIR_OPTIONS)
        if unknown:
            raise ParameterError(f"DuplexModel: unknown pair option(s) {', '.join(unknown)}; "
                                 f"options: {', '.join(sorted(_PAIR_OPTIONS))}")
        if options.get("axisymmetric"):
            raise ParameterError(
                "DuplexModel: pair_options axisymmetric=True cannot be honoured: one "
                "representative ball per row has no radial or tilt load path, so the studies' "
                "radial/tilt loads, 5x5 stiffness and modes would be wrong; build the pair with "
                "duplex_pair(..., axisymmetric=True) for pure axial loads"
            )
        self.pair = duplex_pair(self.bearing, self.arrangement, **options)
        self.geometry = self.pair.geometry
        self.system = assemble(self.pair)
        spec = self.pair.shaft_spec
        self.mass = np.diag([spec.m, spec.m, spec.m, spec.jt, spec.jt])

    # ------------------------------------------------------------------ configurations
    def _geometry(self, bearing) -> BearingGeometry:
        if bearing is None:
            return self.geometry
        g = resolve_bearing(bearing)
        ref = self.geometry
        same = (g.ball_count, g.ball_diameter, g.pitch_diameter, g.fi, g.fo) == (
            ref.ball_count, ref.ball_diameter, ref.pitch_diameter, ref.fi, ref.fo)
        if not same:
            raise ParameterError(f"DuplexModel: bearing {g.designation} differs from "
                                 f"{ref.designation} in more than contact angle and preload; "
                                 "build a DuplexModel for it")
        return g

    def preload_force(self, preload: str | float | None = None, bearing=None,
                      contact_angle: float | None = None) -> float:
        """Nominal preload [N] of a configuration.

        Parameters
        ----------
        preload : {"light", "medium", "heavy"} or float, optional
            Preload class of ``bearing`` or axial preload [N] (checked > 0). Default: the
            pair's own, i.e. its preload class or value, or for a DF/DB pair built with
            ``spacer_offset`` the preload that offset gives (rigid housing, no speed effects).
        bearing : str or BearingGeometry, optional
            A bearing of the same row geometry (default: the model's).
        contact_angle : float, optional
            Free contact angle [rad]; only used for the preload of a spacer offset.

        Returns
        -------
        float
        """
        g = self._geometry(bearing)
        if preload is None and self.pair.preload is None:
            return offset_preload(g, self.pair.spacer_offset, self.arrangement,
                                  self._contact_angle(contact_angle, bearing))
        return preload_force(g, self.pair.preload if preload is None else preload)

    def _contact_angle(self, contact_angle: float | None, bearing) -> float | None:
        if contact_angle is not None or bearing is not None:
            return contact_angle
        return self.pair.contact_angle

    def parameters(self, preload: str | float | None = None, contact_angle: float | None = None,
                   speed: float | None = None, ball_position_angle: float | None = None,
                   bearing: str | BearingGeometry | None = None) -> dict[str, float]:
        """Parameter overrides of one configuration.

        Every argument left at None takes the value the pair was built with (the
        configuration options of ``pair_options``, else the defaults of
        :class:`~bearingsim.assemblies.duplex.DuplexOptions`).

        Parameters
        ----------
        preload : {"light", "medium", "heavy"} or float, optional
            Preload class of ``bearing`` or axial preload [N]. Default: the pair's preload;
            for a DF/DB pair built with ``spacer_offset``, that spacer width difference [m]
            (kept as it is when the contact angle or bearing changes). A DT pair keeps its
            ``spacer_offset`` (spacer mismatch) in every configuration.
        contact_angle : float or str, optional
            Free contact angle [rad], or with a unit ("15 deg"). Default: the pair's, or that
            of ``bearing`` when ``bearing`` is given.
        speed : float or str, optional
            Shaft speed [rad/s], or with a unit ("3000 rpm") (default: the pair's); warned
            above the pair's limiting speed, refused beyond twice it.
        ball_position_angle : float or str, optional
            Azimuth of ball 0 of both rows [rad], or with a unit (default: the pair's).
        bearing : str or BearingGeometry, optional
            A bearing of the same row geometry (default: the model's).

        Returns
        -------
        dict
            Parameter values by dotted name.
        """
        pair = self.pair
        g = self._geometry(bearing)
        if contact_angle is not None:
            contact_angle = si_option(contact_angle, "contact_angle", "rad", "DuplexModel")
        contact_angle = self._contact_angle(contact_angle, bearing)
        speed = pair.speed if speed is None else si_option(speed, "speed", "rad/s",
                                                           "DuplexModel")
        check_pair_speed(g, speed, f"DuplexModel({g.designation})",
                         self.preload_force(preload, bearing))
        if speed != 0.0 and not pair.row[0].speed_effects:
            raise ParameterError(
                f"DuplexModel: speed = {speed:g} rad/s, but the pair was assembled without speed "
                f"effects, so the speed would change nothing; build the model with "
                f"pair_options={{'speed_effects': True}} (or a speed in pair_options)")
        ball_position_angle = pair.ball_position_angle if ball_position_angle is None else \
            si_option(ball_position_angle, "ball_position_angle", "rad", "DuplexModel")
        rp = row_parameters(g, contact_angle, ball_position_angle, self._smooth())
        out = {"shaft.speed": float(speed)}
        for k in range(2):
            out.update({f"row[{k}].alpha0": rp.alpha0, f"row[{k}].K_i": rp.K_i,
                        f"row[{k}].K_o": rp.K_o, f"row[{k}].psi0": rp.psi0})
        if self.arrangement == "DT":
            force = preload_force(g, pair.preload if preload is None else preload)
            out["spring.Fz"] = ARRANGEMENTS["DT"][0] * force
            out["inner_spacer.width_difference"] = pair.spacer_width_difference
        elif preload is None and pair.preload is None:
            out["inner_spacer.width_difference"] = pair.spacer_offset
        else:
            force = preload_force(g, pair.preload if preload is None else preload)
            out["inner_spacer.width_difference"] = _spacer_offset(g, float(force),
                                                                  self.arrangement, rp.alpha0)
        return out

    def _smooth(self) -> float:
        return float(self.system.p0()[self.system.parameter_names.index("row[0].smooth")])

    def _guess(self, params: dict[str, float]) -> np.ndarray:
        x = self.system.x0()
        s0 = ARRANGEMENTS[self.arrangement][0]
        if self.arrangement == "DT":
            g = self.geometry
            rp = row_parameters(g, params["row[0].alpha0"], smooth=self._smooth())
            delta = axial_approach(rp, g.ball_count, 0.5 * abs(params["spring.Fz"]))
        else:
            delta = 0.5 * abs(params["inner_spacer.width_difference"])
        x[self.system.state_names.index("shaft.z")] = s0 * delta
        return x

    # ------------------------------------------------------------------ analyses
    def equilibrium(self, loads: dict[str, float] | None = None, **config: Any) -> Equilibrium:
        """Quasi-static equilibrium under the preload and external loads.

        Parameters
        ----------
        loads : dict, optional
            External loads at the shaft's centre of mass by name: "Fx", "Fy", "Fz" [N],
            "Mx", "My" [N m] (numbers, or numbers with a unit: "2 kN", "30 N m").
        **config
            Configuration, see :meth:`parameters`.

        Returns
        -------
        Equilibrium

        Raises
        ------
        ParameterError
            For loads that bring the pair's static equivalent load beyond 10 x its static load
            rating (ISO 76 rules for pairs:
            :func:`~bearingsim.assemblies.duplex.limits.check_pair_loads`), or a load input
            beyond its bound.

        Warns
        -----
        RowUnloadedWarning
            If a row carries no load (its stiffness is then zero), or a DT pair's axial load
            acts against its loaded direction beyond the spring preload.
        PlasticDeformationWarning
            Above the pair's static load rating.
        """
        params = self.parameters(**config)
        inputs = _load_inputs(loads)
        where = f"DuplexModel({self.geometry.designation} {self.arrangement})"
        check_pair_loads(self.pair.options, {k.split(".")[1]: v for k, v in inputs.items()},
                         where)
        if self.arrangement == "DT":
            _check_reverse_thrust(inputs.get("shaft.Fz", 0.0), params["spring.Fz"], where)
        with warnings.catch_warnings():  # the loads together were rated just above
            warnings.filterwarnings("ignore", category=PlasticDeformationWarning)
            x = self._solve(inputs, params)
        return self._equilibrium(x, inputs, params)

    def _solve(self, inputs: dict[str, float], params: dict[str, float]) -> np.ndarray:
        guess = self._guess(params)
        try:
            return steady_state(self.system, inputs=inputs, parameters=params, x_guess=guess,
                                residual_tol=_ACCEL_TOL)
        except SimulationError:
            pass
        x = guess  # load continuation from the preloaded state
        for step in np.linspace(0.0, 1.0, 11):
            scaled = {k: step * v for k, v in inputs.items()}
            x = steady_state(self.system, inputs=scaled, parameters=params, x_guess=x,
                             residual_tol=_ACCEL_TOL)
        return x

    def _equilibrium(self, x, inputs, params) -> Equilibrium:
        u = self.system.u_default()
        for name, val in inputs.items():
            u[self.system.input_names.index(name)] = val
        obs = self.system.observe(0.0, x, u, self.system.p0(params))
        z = self.geometry.ball_count

        def per_ball(key):
            return np.array([[obs[f"row[{k}].{key}[{j}]"] for j in range(z)] for k in range(2)])

        eq = Equilibrium(np.array([obs[n] for n in _POSITIONS]), x, inputs, params,
                         per_ball("Q_i"), per_ball("Q_o"), per_ball("alpha_i"),
                         per_ball("alpha_o"), per_ball("delta"), obs["inner_spacer.force"])
        for k in range(2):
            if eq.Q_i[k].max() < _UNLOADED:
                warnings.warn(
                    f"row[{k}] of the {self.arrangement} pair carries no load (largest ball "
                    f"load {eq.Q_i[k].max():.2g} N < {_UNLOADED:g} N): the spacer or the "
                    "external load unloads it completely and it adds no stiffness",
                    RowUnloadedWarning, stacklevel=2)
        return eq

    def stiffness(self, eq: Equilibrium) -> np.ndarray:
        """5x5 stiffness matrix at an equilibrium, from the exact Jacobian (no differences).

        ``K = C^-1``, ``C = -(A^-1 B)`` restricted to the shaft displacements and the external
        loads, with ``A = d(dx/dt)/dx`` and ``B = d(dx/dt)/du`` from the system's compiled exact
        Jacobians (``jac_x``, ``jac_u``) at the equilibrium.

        Parameters
        ----------
        eq : Equilibrium
            An equilibrium of this model (:meth:`equilibrium`).

        Returns
        -------
        ndarray
            5x5 stiffness matrix (N/m, N, N m/rad) in the order of ``DOFS``.
        """
        return static_stiffness(self.system, eq.state, _POSITIONS, _LOADS, eq.inputs,
                                eq.parameters)

    def modes(self, loads: dict[str, float] | None = None, loss_factor: float = LOSS_FACTOR,
              **config: Any) -> Modes:
        """Natural frequencies and named mode shapes of one configuration.

        Parameters
        ----------
        loads : dict, optional
            External loads (see :meth:`equilibrium`).
        loss_factor : float
            Loss factor eta [-].
        **config
            Configuration, see :meth:`parameters`.

        Returns
        -------
        Modes
            Natural frequencies [Hz] and mode shapes.
        """
        eq = self.equilibrium(loads, **config)
        return modal_analysis(self.stiffness(eq), self.mass, loss_factor)


def _load_inputs(loads: dict[str, float] | None) -> dict[str, float]:
    out = {}
    for key, val in (loads or {}).items():
        name = key if key.startswith("shaft.") else f"shaft.{key}"
        if name not in _LOADS:
            raise ParameterError(f"unknown load {key!r}; loads: Fx, Fy, Fz [N], Mx, My [N m]")
        unit = "N.m" if name[-2] == "M" else "N"
        out[name] = si_option(val, f"load {key}", unit, "DuplexModel.equilibrium")
    return out
