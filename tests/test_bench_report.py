"""The benchmark report's header: notes of partial runs that a later run supersedes go."""

from bench.run_all import superseded_notes_dropped

LABELS = ["per-call cost", "sweep scaling", "FMU stepper", "FMU export time", "a, b"]

HEAD = (
    "# Benchmarks\n\nTotal run time: 10 s.\n\n"
    "Sections per-call cost re-run by `python -m bench.run_all --only 'per-call cost'` on "
    "day 1 (5 s); other sections are from the full run above or the lines here.\n"
    "Section FMU export time run by `python -m bench.run_all --only 'FMU export time'` on "
    "day 1 (6 s); other sections are from the full run above or the lines here.\n\n"
    "Sections FMU stepper, FMU export time, a, b re-run by `x` on day 2 (7 s); other sections "
    "are from the full run above or the lines here.\n\n"
    "Sections sweep scaling, per-call cost re-run by `y` on day 3 (8 s); other sections are "
    "from the full run above or the lines here.\n\n"
    "## Machine\n")


def test_a_later_run_of_a_section_supersedes_the_earlier_note():
    head = superseded_notes_dropped(HEAD, [], LABELS)
    assert "day 1" not in head  # both day-1 sections were run again later
    assert "Sections FMU stepper, FMU export time, a, b re-run by `x` on day 2" in head
    assert "Sections sweep scaling, per-call cost re-run by `y` on day 3" in head
    assert head.startswith("# Benchmarks\n\nTotal run time: 10 s.\n\nSections FMU stepper")
    assert head.endswith("lines here.\n\n## Machine\n")


def test_a_rerun_trims_the_notes_of_its_sections_and_keeps_the_others():
    head = superseded_notes_dropped(HEAD, ["sweep scaling", "FMU export time"], LABELS)
    assert "Sections FMU stepper, a, b re-run by `x` on day 2" in head  # a label with a comma
    assert "Section per-call cost re-run by `y` on day 3" in head
    assert "sweep scaling" not in head and "FMU export time" not in head.split("`x`")[0]


def test_a_header_without_notes_is_unchanged():
    head = "# Benchmarks\n\nTotal run time: 10 s.\n\n## Machine\n"
    assert superseded_notes_dropped(head, ["per-call cost"], LABELS) == head
