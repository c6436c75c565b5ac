"""boxgen.dask: resampling as a dask.array, one task per block of the output grid.

resample() builds a graph whose blocks each evaluate their own grid points only (through the same
C++ path as boxgen.resample, so .compute() equals it bit for bit). The volume (prefiltered once,
here) and the filter are single keys of the graph: a distributed scheduler ships them to each
worker once, not once per block. docs/python.md says how to run it on a cluster.
"""
import itertools

import numpy as np
import dask.array as da
from dask.base import tokenize
from dask.highlevelgraph import HighLevelGraph

from . import _core


def _shape3(shape):
    if isinstance(shape, (int, np.integer)):
        return (int(shape),) * 3
    shape = tuple(int(s) for s in shape)
    if len(shape) != 3:
        raise ValueError(f"shape must be one integer or three, got {shape}")
    return shape


def _block(volume, filter, lo, hi, shape, begin, end, affine=None):
    # The volume holds the coefficients already: no prefilter, no extension.
    return _core._resample_block(volume, filter, None, lo, hi, shape, (begin, end), "strict",
                                 affine=affine)


def resample(volume, filter, prefilter=None, lo=None, hi=None, shape=None, chunks=64,
             boundary=None, *, affine=None, like=None):
    """boxgen.resample(volume, filter, prefilter, lo, hi, shape, boundary, affine=, like=) as a
    dask.array of `chunks`.

    chunks: anything dask.array accepts for this shape (an integer, a tuple, "auto", ...).
    The arguments are checked here, as boxgen.resample checks them, before any graph is built.
    The prefilter (interp included, which needs the whole volume) and the boundary run once,
    here; the blocks then evaluate the coefficients. like= (an image file) is read once, here:
    its shape and affine (oblique included), so the blocks are those of affine= with them.
    """
    if sum(x is not None for x in (lo, affine, like)) > 1:
        raise ValueError("give one of lo and hi, affine or like")
    if like is not None:
        if shape is not None:
            raise ValueError("like gives the grid's shape: give like or shape, not both")
        shape, affine = _core._image_grid(str(like))
    shape = _shape3(64 if shape is None else shape)
    volume = filter.prefilter_volume(volume, prefilter or "none", boundary)
    if (lo is None) != (hi is None):
        raise ValueError("give both lo and hi, or neither")
    if affine is not None:
        affine = np.array(affine, dtype=np.float64)  # a copy the caller cannot change later
    elif lo is None and volume.frame is None:  # an oblique volume's is refused by the blocks
        lo, hi = filter.default_box(volume)
    if lo is not None:
        lo = tuple(float(x) for x in lo)
        hi = tuple(float(x) for x in hi)
    # The corners and the grid are checked once, by the block holding both corners.
    _core._resample_block(volume, filter, None, lo, hi, shape, ((0, 0, 0), (1, 1, 1)), "strict",
                          affine=affine)
    _core._resample_block(volume, filter, None, lo, hi, shape,
                          (tuple(s - 1 for s in shape), shape), "strict", affine=affine)
    chunks = da.core.normalize_chunks(chunks, shape, dtype=np.float64)
    token = tokenize(volume.samples, volume.lattice_rows, volume.coset_offsets, volume.spacings,
                     volume.affine, filter.name, filter.spec, filter.lattice_rows, lo, hi, affine,
                     shape, chunks)
    name = "boxgen-resample-" + token
    volume_key = "boxgen-volume-" + token
    filter_key = "boxgen-filter-" + token
    graph = {volume_key: volume, filter_key: filter}
    starts = [np.concatenate(([0], np.cumsum(c)[:-1])).astype(int).tolist() for c in chunks]
    for index in itertools.product(*(range(len(c)) for c in chunks)):
        begin = tuple(starts[a][index[a]] for a in range(3))
        end = tuple(begin[a] + chunks[a][index[a]] for a in range(3))
        graph[(name,) + index] = (_block, volume_key, filter_key, lo, hi, shape, begin, end,
                                  affine)
    layers = HighLevelGraph.from_collections(name, graph, dependencies=())
    return da.Array(layers, name, chunks, dtype=np.float64)
