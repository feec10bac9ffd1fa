"""Sweep table cells and arguments found wrong by a new-user trial (each failed before its fix).

* The steady-state time constant of a point reached the table as numpy's float64, whose repr
  (numpy 2) is ``np.float64(0.2857...)``: ``pandas.read_csv`` read the column as text.
* ``--chunk 0`` (or -1) crashed deep in the feeder with ``IndexError`` after the table's header
  was written, and the header-only table then blocked the next sweep into the folder.
* A scheduler that does not answer left such a header-only table too, after dask's OSError.
"""

import dask
import numpy as np
import pytest

from bearingsim.errors import ParameterError
from bearingsim.scenes.sweep import SweepError, run_sweep
from bearingsim.scenes.sweep_table import cell


@pytest.mark.parametrize("value, text", [(np.float64(0.2857549052511293), "0.2857549052511293"),
                                         (0.1, "0.1"), (np.float64("nan"), "nan"), (3, "3")])
def test_a_cell_is_the_number_itself(value, text):
    assert cell(value) == text
    if text != "nan":
        assert float(cell(value)) == value  # round trip


@pytest.mark.parametrize("chunk", [0, -1, 1.5])
def test_a_chunk_below_one_point_is_refused_before_anything_is_written(tmp_path, chunk):
    with pytest.raises(ParameterError, match=r"chunk \(points per task, --chunk\) = .* is "
                                             r"outside the valid range \[1, inf\)|whole number"):
        run_sweep("deep_groove_radial", [{}], out=tmp_path / "out", chunk=chunk)
    assert not (tmp_path / "out").exists()


def test_a_scheduler_that_does_not_answer_leaves_no_table(tmp_path):
    """Before: dask's OSError after its connect timeout, and the table's header row in the
    folder, so that the next sweep there asked for --resume or --overwrite."""
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}), \
            pytest.raises(SweepError, match=r"cannot reach the dask scheduler "
                                            r"tcp://127.0.0.1:1: .*after 1 s"):
        run_sweep("deep_groove_radial", [{}], out=tmp_path / "out",
                  scheduler="tcp://127.0.0.1:1")
    assert list((tmp_path / "out").iterdir()) == []
