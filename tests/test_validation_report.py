"""The validation report (tools/validation_report.py, make validate): each headline check within
the tolerance it states, sources cited, and the committed docs/validation.md names every check."""

from __future__ import annotations

from pathlib import Path

import pytest

from tools.validation_report import CHECKS, TEST_FILES, UNVERIFIED, evaluate

DOC = Path(__file__).resolve().parent.parent / "docs" / "validation.md"


@pytest.mark.parametrize(("check", "value", "error"), evaluate(),
                         ids=lambda v: getattr(v, "quantity", None))
def test_each_check_is_within_its_tolerance(check, value, error):
    assert abs(error) <= check.tolerance, (check.quantity, value, check.reference)


def test_every_check_cites_a_source_and_the_report_lists_it():
    text = DOC.read_text(encoding="utf-8")
    assert len(CHECKS) >= 25 and UNVERIFIED
    for check in CHECKS:
        assert check.source and check.unit and check.tolerance >= 0.0
        assert f"| {check.quantity} | {check.source} |" in text
    for name in TEST_FILES:
        assert (DOC.parent.parent / name).is_file()
        assert name in text
    assert "**outside**" not in text
