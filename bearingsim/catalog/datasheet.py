"""User bearings from a datasheet file, in catalogue units.

A datasheet is a CSV file with the columns of the built-in ``bearings.csv`` or a TOML file with
one ``[[bearing]]`` table per bearing and the same keys; only ``designation, d_mm, D_mm, B_mm, Z,
Dw_mm, dm_mm`` are required::

    [[bearing]]
    designation = "MY6005"
    d_mm = 25
    D_mm = 47
    B_mm = 12
    Z = 10
    Dw_mm = 6.35
    dm_mm = 36
    Pd_um = 12
    C_kN = 11.2
    C0_kN = 5.85
    lim_speed_rpm = 19000

Missing keys take the catalogue's rules: ``fi``/``fo`` 0.52/0.53 (deep groove) or 0.525/0.515
(angular contact, ``alpha_deg`` > 0), ``alpha_deg`` 0, ``Pd_um`` 0 (give the clearance),
ratings, speeds and preload classes absent; the defaulted fields are listed in ``estimated``.

A bearing with an effective roller length ``Lwe_mm`` is a cylindrical roller bearing (NU), with
the columns of the built-in ``cylindrical_rollers.csv``: ``designation, d_mm, D_mm, B_mm, Z,
Dw_mm, Lwe_mm, dm_mm`` required, ``Pd_um`` (0 when left out), ``C_kN``, ``C0_kN``, ``Pu_kN``,
``ref_speed_rpm``, ``lim_speed_rpm`` and ``explorer`` (1 for an SKF Explorer bearing) optional.
"""

from __future__ import annotations

import csv
import re
import sys
from pathlib import Path
from typing import Any

from bearingsim.catalog.geometry import BearingGeometry
from bearingsim.catalog.rollers import RollerBearingGeometry, roller_row_to_geometry
from bearingsim.catalog.table_rows import row_to_geometry
from bearingsim.errors import BearingsimError, CatalogError
from bearingsim.files import FileAccessError, open_regular

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["REQUIRED_KEYS", "ROLLER_REQUIRED_KEYS", "read_datasheet"]

REQUIRED_KEYS = ("designation", "d_mm", "D_mm", "B_mm", "Z", "Dw_mm", "dm_mm")
"""Keys every datasheet ball bearing gives (catalogue units: mm)."""
ROLLER_REQUIRED_KEYS = ("designation", "d_mm", "D_mm", "B_mm", "Z", "Dw_mm", "Lwe_mm", "dm_mm")
"""Keys every datasheet cylindrical roller bearing gives (its ``Lwe_mm`` makes it one)."""
_ROLLER_OPTIONAL_KEYS = ("Pd_um", "C_kN", "C0_kN", "Pu_kN", "ref_speed_rpm", "lim_speed_rpm",
                         "explorer", "estimated", "source")
_ROLLER_NUMBER_KEYS = ("Pd_um", "C_kN", "C0_kN", "Pu_kN", "ref_speed_rpm", "lim_speed_rpm",
                       "explorer")
_OPTIONAL_KEYS = ("fi", "fo", "alpha_deg", "Pd_um", "C_kN", "C0_kN", "ref_speed_rpm",
                  "lim_speed_rpm", "preload_light_N", "preload_medium_N", "preload_heavy_N",
                  "estimated", "source")
_NUMBER_KEYS = ("fi", "fo", "alpha_deg", "Pd_um", "C_kN", "C0_kN", "ref_speed_rpm",
                "lim_speed_rpm", "preload_light_N", "preload_medium_N", "preload_heavy_N")
_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,39}")
"""A key a message may quote (anything else may be a file's content)."""
_DESIGNATION = re.compile(r"[A-Za-z0-9][A-Za-z0-9 ._/\-]{0,29}")
_MAX_BYTES = 10_000_000
"""Largest datasheet file read [bytes] (the built-in catalogue has about 10 kB)."""


def _checked_row(entry: dict[str, Any], where: str, required: tuple[str, ...],
                 optional: tuple[str, ...], numbers: tuple[str, ...], kind: str
                 ) -> dict[str, str]:
    """The entry's cells as text, its keys and numbers checked."""
    unknown = sorted(set(entry) - set(required) - set(optional), key=str)
    if unknown:
        named = [k for k in unknown if isinstance(k, str) and _KEY.fullmatch(k)]
        other = len(unknown) - len(named)
        raise CatalogError(f"{where}: unknown key(s) "
                           + ", ".join(named + ([f"{other} other text(s)"] if other else []))
                           + f"; keys of a {kind}: {', '.join(required + optional)}")
    missing = [k for k in required if str(entry.get(k, "")).strip() == ""]
    if missing:
        raise CatalogError(f"{where}: missing {', '.join(missing)} (mm, {kind}s)")
    row = {k: str(v) for k, v in entry.items()}
    for key in required[1:] + numbers:
        try:
            if row.get(key, "").strip():
                float(row[key])
        except ValueError:
            raise CatalogError(f"{where}: {key} is not a number; expected a number in the "
                               f"unit its name gives") from None
    return row


def _filled(row: dict[str, str], defaults: dict[str, str], optional: tuple[str, ...]
            ) -> dict[str, str]:
    """``row`` with the defaults of its blank cells (listed in ``estimated``) and every
    optional column."""
    estimated = [k for k in defaults if row.get(k, "").strip() == ""]
    for key, value in defaults.items():
        if row.get(key, "").strip() == "":
            row[key] = value
    for key in optional:
        row.setdefault(key, "")
    row["estimated"] = row["estimated"] or ";".join(estimated)
    return row


def _complete(entry: dict[str, Any], where: str) -> dict[str, str]:
    """A ball bearing's entry as a catalogue row (text cells), the catalogue's defaults
    filled in."""
    row = _checked_row(entry, where, REQUIRED_KEYS, _OPTIONAL_KEYS, _NUMBER_KEYS, "ball bearing")
    angular = float(row.get("alpha_deg") or 0.0) > 0.0
    defaults = {"fi": "0.525" if angular else "0.52", "fo": "0.515" if angular else "0.53",
                "alpha_deg": "0", "Pd_um": "0"}
    return _filled(row, defaults, _OPTIONAL_KEYS)


def _complete_roller(entry: dict[str, Any], where: str) -> dict[str, str]:
    """A cylindrical roller bearing's entry as a row of ``cylindrical_rollers.csv``."""
    row = _checked_row(entry, where, ROLLER_REQUIRED_KEYS, _ROLLER_OPTIONAL_KEYS,
                       _ROLLER_NUMBER_KEYS, "roller bearing")
    filled = _filled(row, {"Pd_um": "0"}, _ROLLER_OPTIONAL_KEYS)
    filled["explorer"] = "1" if float(filled["explorer"] or 0.0) == 1.0 else "0"  # (checked)
    return filled


def read_datasheet(path: str | Path) -> list[BearingGeometry | RollerBearingGeometry]:
    """The bearings of a datasheet file (CSV or TOML), validated.

    Parameters
    ----------
    path : str or Path
        ``.csv`` or ``.toml`` file.

    Returns
    -------
    list of BearingGeometry or RollerBearingGeometry
        In file order, SI units (a bearing with ``Lwe_mm``: a roller bearing).

    Raises
    ------
    CatalogError
        For a missing or unreadable file, a missing or unknown key, or a bearing the geometry
        checks refuse, naming the file, the bearing and the key.
    """
    path = Path(path)
    if not path.is_file():
        raise CatalogError(f"bearing datasheet {str(path)!r} not found")
    try:
        with open_regular(path, "bearing datasheet", _MAX_BYTES) as fh:
            text = fh.read()
        if path.suffix.lower() == ".toml":
            entries = tomllib.loads(text).get("bearing", [])
        else:
            lines = [line for line in text.splitlines()
                     if line.strip() and not line.startswith("#")]
            entries = list(csv.DictReader(lines))
    except FileAccessError as exc:
        raise CatalogError(str(exc)) from None
    except UnicodeDecodeError:
        raise CatalogError(f"bearing datasheet {path.name}: not UTF-8 text") from None
    except tomllib.TOMLDecodeError as exc:  # names the line and column, not the text
        raise CatalogError(f"bearing datasheet {path.name}: not valid TOML: {exc}") from None
    except (OSError, csv.Error) as exc:
        raise CatalogError(f"bearing datasheet {path.name}: cannot read it: "
                           f"{type(exc).__name__}") from None
    if not isinstance(entries, list) or not entries:
        raise CatalogError(f"bearing datasheet {path.name}: no bearings (a CSV with a header "
                           f"row, or [[bearing]] tables in TOML)")
    out = []
    for k, entry in enumerate(entries, start=1):
        name = str(entry.get("designation", "") if isinstance(entry, dict) else "")
        where = (f"bearing datasheet {path.name}, bearing {k}"
                 + (f" ({name})" if _DESIGNATION.fullmatch(name) else ""))
        if not isinstance(entry, dict):
            raise CatalogError(f"{where}: not a table of keys")
        roller = "Lwe_mm" in entry
        row = (_complete_roller if roller else _complete)(dict(entry), where)
        row["source"] = row["source"] or f"datasheet {path.name}"
        try:
            out.append(roller_row_to_geometry(row) if roller else row_to_geometry(row))
        except BearingsimError as exc:
            raise CatalogError(f"{where}: {exc}") from None
        except ValueError:
            raise CatalogError(f"{where}: Z is not a whole number") from None
    return out
