# Repeated calls do not grow the process: every Model, Cloud and array is freed.
import gc
import os

import numpy as np

import treesketch


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_repeated_calls_do_not_grow_memory(tree_cloud):
    xyz = np.array(tree_cloud.xyz)

    def once():
        c = treesketch.Cloud.from_numpy(xyz)
        m = treesketch.reconstruct(c)
        v, f = m.mesh()
        cyl = m.cylinders
        m.metrics()
        m.fit_report(c)
        return v.nbytes + f.nbytes + sum(a.nbytes for a in cyl.values())

    for _ in range(3):
        once()  # warm up: allocator pools, TBB's threads
    gc.collect()
    before = rss_bytes()
    per_call = 0
    n = 15
    for _ in range(n):
        per_call = once() + xyz.nbytes
    gc.collect()
    growth = rss_bytes() - before
    # Leaking the arrays and the cloud of every call would grow by n * per_call (and more: the
    # model itself); allow a quarter of that for the allocator's noise.
    assert growth < n * per_call / 4, f"grew {growth} bytes over {n} calls ({per_call} bytes of arrays a call)"


def test_views_do_not_leak_their_cloud():
    xyz = np.zeros((200_000, 3))
    gc.collect()
    before = rss_bytes()
    for _ in range(20):
        c = treesketch.Cloud.from_numpy(xyz)
        a = c.xyz
        del c, a
    gc.collect()
    assert rss_bytes() - before < 2 * xyz.nbytes  # 20 leaked clouds would be 20 x 4.8 MB
