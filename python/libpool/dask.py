"""libpool.batch.run on a Dask cluster: libpool.dask.run(client, layout, strikes).

    from dask.distributed import Client, LocalCluster
    import libpool.dask
    with LocalCluster(n_workers=2, processes=True, threads_per_worker=1) as cluster, \\
            Client(cluster) as client:
        res = libpool.dask.run(client, "rack.json", strikes, chunk_size=2000)

The strikes are cut into chunks of chunk_size rows; client.map sends each chunk to a worker,
which runs it with libpool.batch.run (its own libpool, on `threads` threads), and the chunks'
arrays are concatenated in strike order. Every shot depends only on the layout and its strike,
so the result equals libpool.batch.run(layout, strikes) on one machine, bit for bit.

The workers need libpool installed (pip install ./python, or the same LIBPOOL_PATH and
PYTHONPATH as the client); they need no file: the layout travels as its JSON text.
"""

import numpy as np

from . import batch as _batch

__all__ = ["run", "run_chunk", "DEFAULT_CHUNK_SIZE"]

# Rows per task: at about 10^4 post-break shots/s per core a chunk of 1000 is 0.1 s of work,
# well above Dask's per-task overhead (a few ms; bench/batch/bench_dask.py measures it).
DEFAULT_CHUNK_SIZE = 1000

# The per-shot arrays of BatchResult, concatenated along the shots.
_ROW_FIELDS = ("ball", "strikes", "stop_reason", "events", "end_time", "first_hit", "pos",
               "state", "pocketed", "off_table")


def _layout_text(layout):
    """The layout as JSON text (validated here, so bad input fails before any task is sent)."""
    if isinstance(layout, _batch.Layout):
        raise TypeError("layout: pass the document (path, JSON text or dict), not a Layout: "
                        "the workers parse it themselves")
    text = _batch.layout_text(layout)
    return text, _batch.load_layout(text)


def run_chunk(layout_text, rows, threads=1):
    """One task: libpool.batch.run of rows (n x 6: ball, speed, phi, theta, a, b) on the worker."""
    return _batch.run(layout_text, rows, workers=threads)


def _concatenate(parts, ball_ids):
    fields = {"ball_ids": ball_ids}
    for name in _ROW_FIELDS:
        fields[name] = np.concatenate([getattr(p, name) for p in parts])
    fields["error"] = [e for p in parts for e in p.error]
    return _batch.BatchResult(**fields)


def run(client, layout, strikes, chunk_size=DEFAULT_CHUNK_SIZE, threads=1, ball=None):
    """Runs every strike on the layout on the Dask cluster of `client` and returns the
    BatchResult of libpool.batch.run(layout, strikes, ball=ball): the same arrays, bit for bit.

    layout, strikes, ball: as libpool.batch.run (strike rows are completed from the layout's
      base strike here, so the workers get plain rows of 6 numbers).
    chunk_size: strikes per task (>= 1).
    threads: libpool.batch.run threads inside each task (1 fits a worker process per core).
    Bad input raises ValueError before any task is sent; a task's error is raised here."""
    chunk_size = int(chunk_size)
    if chunk_size < 1:
        raise ValueError("chunk_size: must be >= 1")
    threads = int(threads)
    if threads < 1:
        raise ValueError("threads: must be >= 1")
    text, lay = _layout_text(layout)
    ids = lay.ball_ids
    if ball is None:
        base_ball = lay.strike_ball if lay.strike_ball is not None else ids[0]
    else:
        base_ball = _batch._ffi_int32(ball, "ball")
        if base_ball not in ids:
            raise ValueError(f"ball: no ball of the layout has id {base_ball}")
    ball_col, values = _batch._strike_table(strikes, base_ball, lay.strike)
    rows = np.empty((len(ball_col), 6), dtype=np.float64)
    rows[:, 0] = ball_col  # int32 ids are exact in float64
    rows[:, 1:] = values
    n = len(rows)
    if n == 0:
        return run_chunk(text, rows, threads)
    # A key of its own (hash=False): with the content's hash, a run right after another on the
    # same layout could see the scheduler drop the key when the earlier run releases it.
    [layout_future] = client.scatter([text], broadcast=True, hash=False)
    chunks = [rows[i:i + chunk_size] for i in range(0, n, chunk_size)]
    futures = client.map(run_chunk, [layout_future] * len(chunks), chunks,
                         [threads] * len(chunks), pure=False)
    parts = client.gather(futures)
    return _concatenate(parts, np.array(ids, dtype=np.int32))
