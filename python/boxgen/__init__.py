"""boxgen: exact box-spline analysis and fast reconstruction on any lattice.

The compiled part (boxgen._core, python/*.cpp) wraps the same libraries as the programs
boxgen and boxrecon; docs/python.md is the reference. boxgen.dask resamples in chunks with Dask.
"""
from ._core import (Filter, Volume, analyze, bbform, emit, filters, kernel, metrics, pieces,
                    prefilter, read_volume, resample, sample, set_threads, spectrum,
                    test_functions, threads, write_volume)
from .exact import eval  # noqa: A004 (boxgen.eval, as `boxgen eval`)

# eval is left out, so that `from boxgen import *` does not hide Python's built-in eval.
__all__ = ["Filter", "Volume", "analyze", "bbform", "emit", "filters", "kernel", "metrics",
           "pieces", "prefilter", "read_volume", "resample", "sample", "set_threads", "spectrum",
           "test_functions", "threads", "write_volume"]
