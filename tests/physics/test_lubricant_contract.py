"""The lubricant contract (bearingsim.physics.lubricant.check_lubricant_contract) is checked
where a lubricant is defined: register_lubricant, the bearingsim.lubricants entry points,
as_lubricant for objects; and the one registry pattern (bearingsim.registry.Registry) that
assemblies, bearings and lubricants share."""

from __future__ import annotations

import textwrap
import warnings

import pytest

from bearingsim.catalog import get_bearing
from bearingsim.errors import CatalogError, ParameterError
from bearingsim.physics.friction import skf_friction_torque
from bearingsim.physics.lubricant import (
    LUBRICANTS,
    Dry,
    Lubricant,
    Oil,
    as_lubricant,
    check_lubricant_contract,
    get_lubricant,
    known_lubricants,
    register_lubricant,
)
from bearingsim.registry import NameTakenError, PluginWarning, Registry
from bearingsim.scenes.registry import get_spec


class NoBoundaryFriction(Lubricant):
    """A lubricant written without mu_bl (the SKF model's boundary friction)."""

    def __init__(self):
        self.name, self.method, self.temperature, self.mu_ehl = "bare oil", "oil_bath", 313.15, 0.05
        self._oil = Oil.from_iso_vg(32)

    def kinematic_viscosity(self, T=None):  # noqa: N803
        return self._oil.kinematic_viscosity(T)

    def density(self, T=None):  # noqa: N803
        return self._oil.density(T)

    def pressure_viscosity(self, T=None):  # noqa: N803
        return self._oil.pressure_viscosity(T)

    def traction_coefficient(self, slip_speed):
        return self._oil.traction_coefficient(slip_speed)

    def churning_factor(self):
        return 1.0

    def describe(self):
        return "bare oil"


def test_a_lubricant_without_mu_bl_fails_deep_in_friction_without_the_check():
    """What the contract prevents: the SKF model reaches for mu_bl and fails there."""
    with pytest.raises(AttributeError, match="mu_bl"):
        skf_friction_torque(omega_rel=100.0, dm=0.0385, lubricant=NoBoundaryFriction(),
                            series="62", Fr=1000.0, Fa=100.0, C0=7800.0, d=0.025, D=0.052)


def test_a_lubricant_without_mu_bl_is_refused_where_it_is_defined():
    message = r"lubricant 'bare oil' has no mu_bl \[-\] \(boundary .*\); give it a value in " \
              r"\[0, 2\] -"
    with pytest.raises(ParameterError, match=message):
        register_lubricant("bare oil", lambda **kw: NoBoundaryFriction())
    assert "bare oil" not in known_lubricants()
    with pytest.raises(ParameterError, match=r"my_bearing.lubrication: lubricant 'bare oil' "
                                             r"has no mu_bl"):
        as_lubricant(NoBoundaryFriction(), "my_bearing.lubrication")


@pytest.mark.parametrize(("change", "match"), [
    ({"mu_bl": 3.0}, r"lubricant 'ISO VG 32'.*mu_bl = 3.* outside the valid range \[0, 2\]"),
    ({"temperature": 900.0}, r"temperature = 900.*\[200, 600\] \[K\]"),
    ({"method": "splash"}, r"method = 'splash' is not a lubrication method; give one of "
                           r"grease, oil_mist"),
    ({"name": ""}, r"needs a name"),
])
def test_every_property_of_the_contract_is_checked(change, match):
    oil = Oil.from_iso_vg(32)
    for key, value in change.items():
        setattr(oil, key, value)
    with pytest.raises(ParameterError, match=match):
        check_lubricant_contract(oil, "test")


def test_the_built_in_lubricants_keep_the_contract():
    for name in known_lubricants():
        assert check_lubricant_contract(get_lubricant(name)) is not None
    assert check_lubricant_contract(Dry(mu=1.5)).mu_bl == 1.5


def test_an_unknown_lubricant_names_close_matches():
    with pytest.raises(CatalogError, match=r"unknown lubricant 'ISO VG 86'; known: ISO VG 10.*"
                                           r"did you mean 'ISO VG 68'"):
        get_lubricant("ISO VG 86")
    with pytest.raises(CatalogError, match=r"unknown bearing '6024'; known: .*did you mean .*"
                                           r"'6204'"):
        get_bearing("6024")
    with pytest.raises(KeyError, match=r"unknown assembly 'duplex_par'.*did you mean "
                                       r"'duplex_pair'"):
        get_spec("duplex_par")


def test_a_taken_name_is_one_error_for_every_registry():
    with pytest.raises(NameTakenError, match="already registered"):
        register_lubricant("iso vg 32", lambda **kw: Oil.from_iso_vg(32))
    registry = Registry("widget", lambda: {"a": 1}, replace_builtin=False)
    with pytest.raises(NameTakenError, match="'a' is a built-in widget"):
        registry.register("a", 2, replace=True)
    registry.register("b", 2)
    assert list(registry) == ["a", "b"] and registry["b"] == 2


@pytest.fixture
def site(tmp_path, monkeypatch):
    root = tmp_path / "site"
    root.mkdir()
    monkeypatch.syspath_prepend(str(root))
    LUBRICANTS.reload_plugins()
    yield root
    LUBRICANTS.reload_plugins()


def _install(root, module, source, entries):
    (root / f"{module}.py").write_text(textwrap.dedent(source), encoding="utf-8")
    info = root / "bsim_oils-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: bsim-oils\nVersion: 0.1\n",
                                   encoding="utf-8")
    lines = "".join(f"{k} = {v}\n" for k, v in entries.items())
    (info / "entry_points.txt").write_text(f"[bearingsim.lubricants]\n{lines}", encoding="utf-8")


def test_a_lubricant_plugin_is_found_by_name_and_a_broken_one_is_a_warning(site):
    _install(site, "bsim_oils_plugin", '''
        from bearingsim.physics.lubricant import Oil


        def spindle_oil(**kw):
            return Oil(10.0, 40.0, 2.7, 100.0, **{"name": "plugin spindle oil", **kw})


        def bad_oil(**kw):
            oil = Oil(10.0, 40.0, 2.7, 100.0, name="bad oil")
            del oil.mu_bl
            return oil
        ''', {"plugin spindle oil": "bsim_oils_plugin:spindle_oil",
              "bad oil": "bsim_oils_plugin:bad_oil"})
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        oil = get_lubricant("Plugin-Spindle-Oil", temperature=343.15)
    assert oil.name == "plugin spindle oil" and oil.temperature == 343.15
    texts = [str(w.message) for w in record if issubclass(w.category, PluginWarning)]
    assert len(texts) == 1 and texts[0].startswith(
        "lubricant plug-in entry point bad oil = bsim_oils_plugin:bad_oil (distribution "
        "bsim-oils 0.1) skipped:") and "has no mu_bl" in texts[0]
    with pytest.raises(CatalogError, match="unknown lubricant 'bad oil'.*has no mu_bl"):
        get_lubricant("bad oil")
