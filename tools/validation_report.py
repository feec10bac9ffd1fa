"""Write ``docs/validation.md``: every model against the published values and independent
references the project has, with the error, in one table, and what is still unverified.

    python -m tools.validation_report docs/validation.md      (make validate)

Two parts:

1. :data:`CHECKS`: headline comparisons evaluated here, each a model quantity, the published or
   independent value, its source (with page) and the tolerance the model is held to; the table
   shows the model's value and its error.
2. The published-value tests (:data:`TEST_FILES`): run with pytest; one row per test function
   with the number of cases, how many passed and the source its docstring cites. Together they
   compare several hundred published numbers (catalogue tables, worked examples, standards).

The report is deterministic (no timings), so CI regenerates it and fails when the committed file
differs (``.ci/run``); ``tests/test_validation_report.py`` holds each check to its tolerance.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import sys
from collections import defaultdict
from collections.abc import Callable
from pathlib import Path

from bearingsim.catalog import get_bearing
from bearingsim.files import atomic_path
from bearingsim.physics import contact_curvature, film, friction, hertz, life
from bearingsim.physics.double_layer_theory import speed_ratio_palmgren
from bearingsim.physics.lubricant import Oil
from bearingsim.physics.lubrication import palmgren_f0
from bearingsim.units import rpm_to_rad_s

ROOT = Path(__file__).resolve().parent.parent

TEST_FILES = (
    "tests/physics/test_published_catalogue_checks.py",
    "tests/physics/test_published_contact_film.py",
    "tests/physics/test_published_examples.py",
    "tests/physics/test_published_roller_checks.py",
    "tests/physics/test_published_tables.py",
    "tests/physics/test_published_textbook_examples.py",
    "tests/studies/test_fidelity_errors.py",
)
"""Test files whose cases compare the models with published values or measured references."""


@dataclasses.dataclass(frozen=True)
class Check:
    """One model quantity against a published or independent value.

    Attributes
    ----------
    model : str
        The model or function checked.
    quantity : str
        What is compared, with the case.
    source : str
        Where the reference value is printed (document, page, table).
    reference : float
        The published value, in ``unit``.
    unit : str
        Unit of ``reference`` and of the computed value.
    compute : callable
        ``compute() -> float``: the model's value in ``unit``.
    tolerance : float
        Largest relative error the model is held to [-] (the reference's rounding or the stated
        accuracy of the comparison).
    """

    model: str
    quantity: str
    source: str
    reference: float
    unit: str
    compute: Callable[[], float]
    tolerance: float


def _e_prime(youngs_modulus: float, poisson_ratio: float) -> float:
    return youngs_modulus / (1.0 - poisson_ratio**2)


def _amesweb():
    rx = 1.0 / (1.0 / 4.90e-3 + 1.0 / 25e-3)
    ry = 1.0 / (1.0 / 4.90e-3 - 1.0 / 5e-3)
    return hertz.hertz_contact(1500.0, rx, ry, _e_prime(210e9, 0.29))


def _eng_tools():
    rx, ry = contact_curvature.raceway_radii(9.525e-3, 46.0e-3, 4.89 / 9.525, 0.0, "inner")
    return hertz.hertz_contact(5.0 * 1000.0 / 9.0, rx, ry, _e_prime(210e9, 0.3),
                               method="hamrock_brewe")


def _rolling_ball_film(distance: float) -> float:
    radius = 1.5e-2
    mass = 7800.0 * 4.0 / 3.0 * math.pi * radius**3
    load = mass * 9.81 * math.cos(math.pi / 4.0)
    speed = math.sqrt(2.0 * (5.0 / 7.0) * 9.81 * math.sin(math.pi / 4.0) * distance)
    res = film.hamrock_dowson(load, speed / 2.0, radius / 2.0, radius / 2.0,
                              _e_prime(2.1e11, 0.3), 0.05, 2.2e-8)
    return float(res.h_min) * 1e6


def _iso281_c(name: str) -> float:
    g = get_bearing(name)
    return float(life.dynamic_load_rating(g.ball_diameter, g.pitch_diameter, g.ball_count))


def _iso76_c0(name: str) -> float:
    g = get_bearing(name)
    return float(life.static_load_rating(g.ball_diameter, g.pitch_diameter, g.ball_count))


def _skf_22208e_phi_ish() -> float:
    parts = friction.skf_friction_components(
        rpm_to_rad_s(3500.0), 0.060, Oil.from_iso_vg(68, temperature=313.15), "62", 2990.0,
        100.0, C0=90e3, d=0.040, D=0.080)
    return float(parts.phi_ish)


def _xy(alpha_deg: float, rows: int, which: int) -> float:
    return float(life.xy_factors(100.0, 1000.0, 1e4, 14.0, math.radians(alpha_deg), rows)[which])


def _torque_level_rs(inner: str, outer: str) -> float:
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.studies.double_layer import steady_ratio

    system = assemble(double_layer_bearing(inner, outer, fidelity="torque",
                                           layer_options={"load_dependent": False}))
    return float(steady_ratio(system, rpm_to_rad_s(10_000.0))[0])


NSK_E1102E = "NSK CAT. No. E1102e, pp. B8-B11"
CHECKS: tuple[Check, ...] = (
    Check("hertz.hertz_contact (exact)", "p_max, ball 4.90 mm in groove 5 mm / race 25 mm, 1500 N",
          "amesweb.info, Contact Stresses in a Steel Ball Bearing (site calculator)", 2193.6,
          "MPa", lambda: _amesweb().max_pressure / 1e6, 0.005),
    Check("hertz.hertz_contact (exact)", "semi-major axis a, same case",
          "amesweb.info (as above)", 2.101, "mm", lambda: _amesweb().a * 1e3, 0.005),
    Check("hertz.hertz_contact (exact)", "semi-minor axis b, same case",
          "amesweb.info (as above)", 0.156, "mm", lambda: _amesweb().b * 1e3, 0.005),
    Check("hertz.hertz_contact (Brewe-Hamrock fits)", "ellipticity k, 6206 inner contact, Fr 1 kN",
          "eng-tools.dev, Hertz Contact Stress in Deep Groove Ball Bearings, case 6206", 12.19,
          "-", lambda: _eng_tools().k, 0.0005),
    Check("hertz.hertz_contact (Brewe-Hamrock fits)", "p0, same case", "eng-tools.dev (as above)",
          1728.0, "MPa", lambda: _eng_tools().max_pressure / 1e6, 0.0005),
    Check("film.hamrock_dowson", "h_min, 30 mm ball rolled 1 cm down an oiled 45 deg plate",
          "Stachowiak & Batchelor, Engineering Tribology, ch. 7 problem (printed answer)", 0.059,
          "um", lambda: _rolling_ball_film(0.01), 0.0085),
    Check("film.hamrock_dowson", "h_min, same ball after 1 m", "(as above)", 0.281, "um",
          lambda: _rolling_ball_film(1.0), 0.0018),
    *(Check("life.dynamic_load_rating (ISO 281)", f"C of {n} from its ball set", NSK_E1102E, c,
            "N", lambda n=n: _iso281_c(n), 0.005)
      for n, c in (("6204", 12800.0), ("6205", 14000.0), ("6206", 19500.0), ("6304", 15900.0))),
    *(Check("life.static_load_rating (ISO 76)", f"C0 of {n} from its ball set", NSK_E1102E, c0,
            "N", lambda n=n: _iso76_c0(n), 0.005)
      for n, c0 in (("6204", 6600.0), ("6205", 7850.0), ("6206", 11300.0), ("6304", 7900.0))),
    Check("life.rating_life, life_hours", "L10h of 6208, Cr 29.1 kN, Fr 2.5 kN, 900 r/min",
          "NSK CAT. No. E1102e, p. A34, Example 1 (approximately 29 000 h)", 29000.0, "h",
          lambda: float(life.life_hours(life.rating_life(29100.0, 2500.0),
                                        rpm_to_rad_s(900.0))), 0.01),
    Check("life.equivalent_dynamic_load", "P of 6208, Fr 2.5 kN, Fa 1 kN, f0 14, C0r 17.9 kN",
          "NSK CAT. No. E1102e, p. A34, Example 3", 3070.0, "N",
          lambda: float(life.equivalent_dynamic_load(2500.0, 1000.0, 17900.0, 14.0)), 0.002),
    Check("life.rating_life, life_hours", "L10h of 6309, C 55.3 kN, P 10 kN, 3000 r/min",
          "SKF General Catalogue 6000, p. 78, Example 1", 940.0, "h",
          lambda: float(life.life_hours(life.rating_life(55.3e3, 10e3), rpm_to_rad_s(3000.0))),
          0.001),
    Check("life.xy_factors", "e, single-row angular contact 20 deg",
          "GOST 18855-2013 (ISO 281:2007 MOD), Table 3, p. 9", 0.57, "-",
          lambda: _xy(20.0, 1, 2), 1e-9),
    Check("life.xy_factors", "Y (Fa/Fr > e), double row 20 deg", "GOST 18855-2013, Table 3, p. 9",
          1.63, "-", lambda: _xy(20.0, 2, 1), 1e-9),
    Check("life.xy_factors", "Y (Fa/Fr > e), single row 45 deg", "GOST 18855-2013, Table 3, p. 9",
          0.50, "-", lambda: _xy(45.0, 1, 1), 1e-9),
    Check("friction.skf_friction_components", "inlet shear factor phi_ish, 22208 E example",
          "SKF General Catalogue 6000, p. 104 (approximately 0.85)", 0.85, "-",
          _skf_22208e_phi_ish, 0.006),
    Check("lubrication.palmgren_f0", "f0, 619 series, oil bath",
          "Timken Engineering Manual, Table 114, p. 184 (series 39)", 1.7, "-",
          lambda: palmgren_f0("deep_groove_ball", "oil_bath", "619"), 1e-9),
    Check("lubrication.palmgren_f0", "f0, 619 series, oil bath",
          "KRW catalogue 2006, p. 117 (619, 160, 60)", 1.75, "-",
          lambda: palmgren_f0("deep_groove_ball", "oil_bath", "619"), 0.03),
    Check("lubrication.palmgren_f0", "f0, 619 series, grease", "KRW catalogue 2006, p. 117", 1.17,
          "-", lambda: palmgren_f0("deep_groove_ball", "grease", "619"), 0.06),
    Check("friction.palmgren_f1", "f1 of a 619 bearing at P0/C0 = 0.1 (model: the study's "
          "0.0009 (P0/C0)^0.55, kept on purpose)", "Schaeffler HR 1 (2006), p. 58: 0.0007 "
          "(P0/C0)^0.5", 0.0007 * 0.1**0.5, "-",
          lambda: float(friction.palmgren_f1("deep_groove_ball", 0.1, 1.0)), 0.15),
    *(Check("double_layer_bearing, torque level", f"Rs of {i}/{o} at 10 000 r/min, no load (M0 "
            "only)", "[studies, section A](studies.md#a-double-layer-bearings): the Dp^4.5 law of "
            "the study (independent closed form)",
            speed_ratio_palmgren(i, o), "-", lambda i=i, o=o: _torque_level_rs(i, o), 0.01)
      for i, o in (("61905", "61907"), ("61905", "61908"), ("61905", "61909"))),
)

UNVERIFIED = (
    "Hertz: no textbook worked example with printed answers (Harris & Kotzalas 209/218, Hamrock, "
    "Boresi); `orthogonal_shear_stress` (tau0, z0) has no published example.",
    "Film thickness inside a bearing: no printed h_min or Lambda of a ball bearing example; the "
    "central film h_c is unchecked.",
    "Lubricant: ASTM D341's own example, a third-temperature data sheet, the density and the Gold "
    "pressure-viscosity defaults.",
    "Palmgren: f0 of the per-type table (series without a catalogue row, vertical shaft, roller "
    "bearings); the deep-groove f1 exponent 0.55 is the study's (catalogues: 0.5).",
    "SKF: the `73B` angular contact constants; the drag coefficient VM (a diagram in both SKF "
    "editions, no printed values), so the ball drag is the Schlichting form.",
    "ISO 281: the reading of the 15 deg abscissa for pairs (the pair's C0).",
    "ISO/TS 16281: checked against the standard's equations computed by hand "
    "(tests/studies/test_deep_groove_statics.py); no worked example of the standard itself.",
    "Double-layer bearing: no measured speed ratio of the study is available as numbers (it states "
    "the trends only, [studies, section A](studies.md#a-double-layer-bearings)); the torque level "
    "is checked against the study's closed-form laws and the ball level against the torque level.",
    "Ball-level dynamics (cage slip, pocket forces): no published measurement is in the project; "
    "checked by conservation, symmetry and agreement between fidelity levels.",
)


def evaluate() -> list[tuple[Check, float, float]]:
    """Every check with the model's value and its relative error."""
    rows = []
    for check in CHECKS:
        value = float(check.compute())
        rows.append((check, value, value / check.reference - 1.0))
    return rows


class _Collector:
    """pytest plugin: outcome of every test case, grouped by test function."""

    def __init__(self) -> None:
        self.cases: dict[str, list[bool]] = defaultdict(list)
        self.docs: dict[str, str] = {}

    def pytest_collection_modifyitems(self, items):  # noqa: D102 - pytest hook
        for item in items:
            key = item.nodeid.split("[")[0]
            doc = inspect.getdoc(getattr(item, "function", None)) or ""
            self.docs[key] = " ".join(doc.split("\n\n")[0].split())

    def pytest_runtest_logreport(self, report):  # noqa: D102 - pytest hook
        if report.when == "call" or (report.when == "setup" and report.outcome != "passed"):
            self.cases[report.nodeid.split("[")[0]].append(report.outcome == "passed")


def run_published_tests() -> _Collector:
    """Run :data:`TEST_FILES` with pytest and collect the outcomes."""
    import pytest

    collector = _Collector()
    code = pytest.main(["-q", "-p", "no:cacheprovider", "-p", "no:randomly",
                        *(str(ROOT / f) for f in TEST_FILES)], plugins=[collector])
    if code not in (0, 1):
        raise RuntimeError(f"pytest exited with {code}")
    return collector


def _fmt(value: float) -> str:
    return f"{value:.6g}"


def report_text(rows: list[tuple[Check, float, float]], collector: _Collector) -> str:
    """The Markdown of ``docs/validation.md``."""
    lines = [
        "# Validation report",
        "",
        "Generated by `make validate` (`python -m tools.validation_report docs/validation.md`); "
        "CI regenerates it and fails when it differs. Every figure comes from the models at "
        "this commit.",
        "",
        "## Headline checks",
        "",
        "| model | quantity | source | published | model | error | held to |",
        "|---|---|---|---|---|---|---|",
    ]
    for check, value, error in rows:
        ok = "" if abs(error) <= check.tolerance else " **outside**"
        lines.append(f"| `{check.model}` | {check.quantity} | {check.source} | "
                     f"{_fmt(check.reference)} {check.unit} | {_fmt(value)} {check.unit} | "
                     f"{error:+.2%}{ok} | {check.tolerance:.2%} |")
    total = sum(len(v) for v in collector.cases.values())
    passed = sum(sum(v) for v in collector.cases.values())
    lines += [
        "",
        "## Published-value tests",
        "",
        f"{total} cases in {len(collector.cases)} tests, {passed} passed. Each compares model "
        "output with values printed in the source its docstring cites (first paragraph shown).",
        "",
        "| test | cases | passed | source and comparison |",
        "|---|---|---|---|",
    ]
    for key in sorted(collector.cases):
        outcomes = collector.cases[key]
        doc = collector.docs.get(key, "").replace("|", "/")
        lines.append(f"| `{key}` | {len(outcomes)} | {sum(outcomes)} | {doc} |")
    lines += ["", "## Not yet verified", ""] + [f"* {item}" for item in UNVERIFIED]
    return "\n".join(lines) + "\n"


def write_report(path: str | Path) -> Path:
    """Evaluate, run the tests, write the report; returns the path."""
    rows = evaluate()
    collector = run_published_tests()
    path = Path(path)
    with atomic_path(path) as tmp:
        Path(tmp).write_text(report_text(rows, collector), encoding="utf-8")
    return path


if __name__ == "__main__":
    print(f"wrote {write_report(sys.argv[1] if len(sys.argv) > 1 else 'docs/validation.md')}")
