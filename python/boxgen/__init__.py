"""boxgen: exact box-spline analysis and fast reconstruction on any lattice.

The compiled part (boxgen._core, python/*.cpp) wraps the same libraries as the programs
boxgen and boxrecon; docs/python.md is the reference. boxgen.dask resamples in chunks with Dask.
"""
from ._core import (Filter, Volume, analyze, filters, kernel, metrics, pieces, prefilter,
                    read_volume, resample, sample, set_threads, spectrum, test_functions,
                    threads, write_volume)

__all__ = ["Filter", "Volume", "analyze", "filters", "kernel", "metrics", "pieces", "prefilter",
           "read_volume", "resample", "sample", "set_threads", "spectrum", "test_functions",
           "threads", "write_volume"]
