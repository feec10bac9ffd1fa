"""The deep-groove ball bearing's quasi-static level: the balls' load distribution under the ring's
loads (:class:`QuasiStaticDeepGroove`)."""

from __future__ import annotations

import math
import numbers
from typing import Any

from bearingsim.components.ball_row import BallRow, row_equilibrium, row_parameters
from bearingsim.components.dynamic import (
    FixedFrame,
    RingLoad,
    TiltGuide,
)
from bearingsim.components.dynamic.ring import check_loads
from bearingsim.components.rolling_element import check_static_rating, load_input_bounds
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.language import Assembly, connect
from bearingsim.validation import (
    check_range,
)


class QuasiStaticDeepGroove(Assembly):
    """Quasi-static deep-groove bearing: a :class:`~bearingsim.components.ball_row.BallRow`
    (``reference="centred"``) between the fixed outer ring and an inner ring in force balance
    with the external load (its displacement is algebraic, solved by the assembler's Newton).

    With ``speed`` > 0 the row uses its Jones-Harris form (centrifugal force, gyroscopic moment)
    at that inner-ring speed; the shaft holds the ring straight (no tilt), so the ring takes no
    moment. The Newton blocks start from the numeric equilibrium at the constant loads
    (:func:`~bearingsim.components.ball_row.row_equilibrium`; load inputs count as 0 there); with
    load inputs at speed the assembler gives the blocks a line search (CasADi's ``newton``
    rootfinder, which generates no C code), without them plain Newton (``fast_newton``).

    Parameters
    ----------
    geometry : BearingGeometry
        Its ``diametral_clearance`` Pd sets the free contact angle.
    loads : dict
        ``Fx, Fy, Fz`` [N]: finite constants, functions of time or None for inputs (missing
        keys are inputs with default 0). ``Mx, My`` may only be absent or 0 (the shaft takes
        the moments); other keys raise :class:`~bearingsim.errors.ParameterError`.
    speed : float
        Constant inner-ring speed [rad/s], >= 0.
    name : str
        Instance name (the prefix of its variables' dotted names).

    Raises
    ------
    ParameterError
        For an unknown load key, a non-finite constant load, a moment load, a speed that is not
        a finite number >= 0 (a function of time or an input needs a dynamic level), or a speed
        at which the balls have no quasi-static equilibrium under the constant loads (the
        message names the speed).
    """

    def __init__(self, geometry, loads: dict[str, Any] | None = None, speed: float = 0.0,
                 name="bearing"):
        super().__init__(name)
        where = "deep_groove_ball_bearing(quasi-static)"
        loads = check_loads(loads, where)
        for key in ("Mx", "My"):
            if key in loads and loads[key] != 0.0:
                raise ParameterError(f"{where}: loads[{key!r}] = {loads[key]!r} [N.m], but the "
                                     f"shaft holds the inner ring straight at this level and "
                                     f"takes the moments; give only Fx, Fy, Fz (or use a dynamic "
                                     f"fidelity with free_tilt=True)")
        if callable(speed) or speed is None or isinstance(speed, bool) \
                or not isinstance(speed, numbers.Real):
            raise ParameterError(f"{where}: speed must be a constant number >= 0 [rad/s], got "
                                 f"{speed!r}; a speed that varies in time or an input "
                                 f"shaft_speed needs a dynamic fidelity")
        speed = float(check_range(speed, "speed", "rad/s", 0.0, where=where))
        geometry.check_speed(speed, where)
        # start values of the Newton blocks (ring translation, ball centres at speed): the
        # equilibrium at the constant loads (inputs count as 0)
        constant = [float(v) if isinstance(v, (int, float)) else 0.0
                    for v in (loads.get(k) for k in ("Fx", "Fy", "Fz"))]
        try:
            start = row_equilibrium(row_parameters(geometry), geometry.ball_count, constant,
                                    speeds=(speed, 0.0), speed_effects=speed > 0.0)
        except SimulationError as exc:
            raise ParameterError(
                f"{where}: no quasi-static ball equilibrium at the inner-ring speed {speed:g} "
                f"rad/s ({speed * 30.0 / math.pi:.0f} r/min) under the loads {constant} N; "
                f"the balls' equilibrium is lost there ({exc})") from None
        check_static_rating(geometry, constant, where)
        self.row = BallRow(geometry, reference="centred", speed_effects=speed > 0.0,
                           centre_start=start.centres)
        # load inputs move the equilibrium away from the start values; at speed the Jones-Harris
        # ball equations then need Newton with a line search (CasADi's "newton": no C code)
        self.needs_line_search = speed > 0.0 and any(
            not isinstance(loads.get(k, None), (int, float)) for k in ("Fx", "Fy", "Fz"))
        self.row.inner_speed = speed
        self.housing = FixedFrame()
        self.guide = TiltGuide()
        self.load = RingLoad({**loads, "Mx": 0.0, "My": 0.0},
                             bounds=load_input_bounds(geometry))
        self.row.inner.guess(**dict(zip(("x", "y", "z"), start.inner.tolist(), strict=True)))
        connect(self.row.outer, self.housing.frame)
        connect(self.row.inner, self.load.frame, self.guide.frame)
