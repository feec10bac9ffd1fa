"""The physics packages that re-export their submodules: ``__all__`` is the union of the
submodules' ``__all__`` and every name in it is importable from the package."""

import importlib

import pytest

PACKAGES = {
    "bearingsim.physics.life": ("iso_281", "iso_76", "lundberg_palmgren", "iso_ts_16281",
                                "modified_life"),
    "bearingsim.physics.friction": ("palmgren", "skf"),
}


@pytest.mark.parametrize("package", sorted(PACKAGES))
def test_package_reexports_every_public_name_of_its_submodules(package):
    pkg = importlib.import_module(package)
    submodules = [importlib.import_module(f"{package}.{name}") for name in PACKAGES[package]]
    names = [name for module in submodules for name in module.__all__]
    assert sorted(pkg.__all__) == sorted(names)
    assert len(set(names)) == len(names)  # no name in two submodules
    for module in submodules:
        for name in module.__all__:
            assert getattr(pkg, name) is getattr(module, name), f"{package}.{name}"
