"""Test configuration.

Hypothesis draws new random examples on every local run (and has found real boundary bugs that
way); in CI (``CI`` set) it runs a fixed, derandomized set so a green submission stays green.
"""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, deadline=None)
if os.environ.get("CI"):
    settings.load_profile("ci")
