"""boxgen.dask.resample: blocks of the output grid as dask tasks, equal to boxgen.resample bit
for bit on dask's threaded scheduler and on a distributed LocalCluster."""
import numpy as np
import pytest

import boxgen
import boxgen.dask

LO, HI, SHAPE, CHUNKS = (-0.7, -0.6, -0.5), (0.6, 0.7, 0.5), (9, 8, 7), (4, 3, 5)


@pytest.fixture(scope="module")
def case():
    return boxgen.sample("ml", 9), boxgen.Filter("m7")


def test_graph_has_one_volume_and_one_task_per_block(case):
    v, f = case
    a = boxgen.dask.resample(v, f, "q2", LO, HI, SHAPE, CHUNKS)
    assert a.shape == SHAPE and a.chunks == ((4, 4, 1), (3, 3, 2), (5, 2))
    graph = dict(a.__dask_graph__())
    volumes = [x for x in graph.values() if isinstance(x, boxgen.Volume)]
    tasks = [x for x in graph.values() if isinstance(x, tuple)]
    assert len(volumes) == 1 and len(tasks) == 3 * 3 * 2
    # Each task evaluates its own block: begin and end tile the grid exactly once.
    covered = np.zeros(SHAPE, dtype=int)
    for task in tasks:
        begin, end = task[-3], task[-2]  # then the affine (None here)
        covered[tuple(slice(b, e) for b, e in zip(begin, end))] += 1
    assert (covered == 1).all()


def test_threaded_equals_resample(case):
    v, f = case
    expected = boxgen.resample(v, f, "q2", LO, HI, SHAPE)
    got = boxgen.dask.resample(v, f, "q2", LO, HI, SHAPE, CHUNKS).compute(scheduler="threads")
    assert np.array_equal(got, expected)
    default = boxgen.dask.resample(v, f, None, shape=6, chunks=4).compute(scheduler="threads")
    assert np.array_equal(default, boxgen.resample(v, f, None, shape=6))
    # interp runs once, on the whole volume, before the blocks.
    interp = boxgen.dask.resample(v, f, "interp", LO, HI, SHAPE, CHUNKS, boundary="clamp")
    assert np.array_equal(interp.compute(scheduler="threads"),
                          boxgen.resample(v, f, "interp", LO, HI, SHAPE, boundary="clamp"))


def test_distributed_equals_resample(case):
    from dask.distributed import Client, LocalCluster
    v, f = case
    expected = boxgen.resample(v, f, "q1", LO, HI, SHAPE)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        got = client.compute(boxgen.dask.resample(v, f, "q1", LO, HI, SHAPE, CHUNKS)).result()
    assert np.array_equal(got, expected)


def test_errors_before_any_graph(case):
    v, f = case
    with pytest.raises(ValueError, match="leaves the region"):
        boxgen.dask.resample(v, f, None, (-9, 0, 0), (0, 1, 1), 4, 2)
    with pytest.raises(ValueError, match="unknown prefilter|prefilter"):
        boxgen.dask.resample(v, f, "q7", LO, HI, 4, 2)


def _turned(degrees, spacing, origin):
    """A voxel-to-world affine turned about z by `degrees`, with these voxel sizes and origin."""
    t = np.radians(degrees)
    turn = np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])
    a = np.eye(4)
    a[:3, :3] = turn @ np.diag(spacing)
    a[:3, 3] = origin
    return a


def test_affine_and_like_equal_resample(case, tmp_path):
    """affine= (an oblique grid) and like= (an oblique NIfTI nibabel writes, read once for its
    shape and affine) give boxgen.resample's values bit for bit, block by block."""
    v, f = case
    affine = _turned(20, (0.11, 0.09, 0.1), (-0.3, -0.35, -0.3))
    expected = boxgen.resample(v, f, "q2", shape=SHAPE, affine=affine)
    got = boxgen.dask.resample(v, f, "q2", shape=SHAPE, chunks=CHUNKS, affine=affine)
    affine[0, 0] = 5  # the graph holds its own copy
    assert np.array_equal(got.compute(scheduler="threads"), expected)
    nib = pytest.importorskip("nibabel")
    like = tmp_path / "like.nii"
    nib.save(nib.Nifti1Image(np.zeros((6, 5, 4), np.float32),
                             _turned(-15, (0.12, 0.1, 0.14), (-0.25, -0.3, -0.2))), str(like))
    expected = boxgen.resample(v, f, "q1", like=str(like))
    got = boxgen.dask.resample(v, f, "q1", chunks=(4, 3, 2), like=like)
    assert got.shape == (6, 5, 4)
    assert np.array_equal(got.compute(scheduler="threads"), expected)
    with pytest.raises(ValueError, match="like or shape"):
        boxgen.dask.resample(v, f, "q1", shape=4, like=like)
    with pytest.raises(ValueError, match="one of lo and hi, affine or like"):
        boxgen.dask.resample(v, f, "q1", LO, HI, affine=affine)
