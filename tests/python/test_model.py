# The automatic model from Python: its arrays, outputs, errors, progress and cancellation.
import json

import numpy as np
import pytest

import treesketch
from conftest import run_cli


def test_cylinder_columns_are_consistent(tree_model):
    c = tree_model.cylinders
    m = len(c["id"])
    assert m > 10
    assert c["start"].shape == (m, 3) and c["end"].shape == (m, 3)
    for key in ("radius", "start_radius", "length", "branch_order", "measured", "parent"):
        assert c[key].shape == (m,)
    assert np.allclose(c["length"], np.linalg.norm(c["end"] - c["start"], axis=1))
    assert (c["radius"] > 0).all() and (c["start_radius"] > 0).all()
    ids = set(c["id"].tolist())
    assert all(p == -1 or p in ids for p in c["parent"].tolist())
    assert (c["branch_order"] == 0).any() and (c["branch_order"] > 0).any()
    assert c["measured"].dtype == np.bool_ and 0 < c["measured"].sum() <= m
    # A measured radius rests on an accepted fit or on the tracked stem's circles (order 0).
    assert c["measured"].sum() <= tree_model.summary["fits_accepted"] + (c["branch_order"] == 0).sum()


def test_the_stem_is_found_on_the_generated_tree(tree_model, tree_mesh):
    # The sparse preset's trunk: the model's height within 10 % of the mesh's.
    height = tree_mesh[0][:, 2].max() - tree_mesh[0][:, 2].min()
    assert tree_model.metrics()["heightM"] == pytest.approx(height, rel=0.1)
    h, d = tree_model.taper
    assert len(h) == len(d) > 2 and h[0] == 0 and np.isfinite(d[0]) and d[0] > 0


def test_mesh_arrays(tree_model):
    v, f = tree_model.mesh()
    assert v.shape[1] == 3 and f.shape[1] == 3 and f.dtype == np.uint32
    assert f.max() < len(v)
    assert len(v) == tree_model.summary["vertices"] and len(f) == tree_model.summary["triangles"]


def test_every_output_reads_back(tree_model, tmp_path):
    tree_model.write(str(tmp_path / "m.obj"))
    v, f = treesketch.read_mesh(str(tmp_path / "m.obj"))
    mv, mf = tree_model.mesh()
    assert np.array_equal(f, mf) and np.allclose(v, mv, atol=1e-6)
    tree_model.write(str(tmp_path / "m.csv"))
    table = np.genfromtxt(tmp_path / "m.csv", delimiter=",", names=True)
    c = tree_model.cylinders
    assert np.array_equal(table["id"], c["id"]) and np.array_equal(table["parent"], c["parent"])
    assert np.allclose(table["radius"], c["radius"], rtol=1e-8)
    assert np.allclose(table["start_radius"], c["start_radius"], rtol=1e-8)
    assert np.array_equal(table["measured"].astype(bool), c["measured"])
    tree_model.write(str(tmp_path / "m.txt"))
    qsm = (tmp_path / "m.txt").read_text().splitlines()
    assert len(qsm) == len(c["id"]) + 1 and "radius" in qsm[0]  # a header, then a row per cylinder
    tree_model.write(str(tmp_path / "m.json"))
    assert len(treesketch.read_sketch(str(tmp_path / "m.json"))) == tree_model.summary["skeleton_nodes"]
    tree_model.write(str(tmp_path / "metrics.out"), kind="metrics")
    assert json.loads((tmp_path / "metrics.out").read_text()) == tree_model.metrics()


def test_a_report_needs_the_cloud(tree_model, tree_cloud, tmp_path):
    with pytest.raises(treesketch.OptionsError, match="cloud"):
        tree_model.write(str(tmp_path / "r.json"), kind="report")
    tree_model.write(str(tmp_path / "r.json"), kind="report", cloud=tree_cloud)
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["model"]["fit"] == tree_model.fit_report(tree_cloud)["fit"]
    assert report["skeletonNodes"] == tree_model.summary["skeleton_nodes"] and report["auto"] is True


def test_write_rejects_unknown_formats(tree_model, tmp_path):
    with pytest.raises(treesketch.OptionsError, match="unknown output extension"):
        tree_model.write(str(tmp_path / "m.stl"))
    with pytest.raises(treesketch.OptionsError, match="kind"):
        tree_model.write(str(tmp_path / "m.obj"), kind="picture")


def test_write_to_an_impossible_place_raises_output_error(tree_model, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(treesketch.OutputError):
        tree_model.write(str(blocker / "m.obj"))


def test_options_change_the_model(tree_cloud, tree_model):
    fine = treesketch.reconstruct(tree_cloud, ring=8)
    assert fine.summary["vertices"] < tree_model.summary["vertices"]
    y_up = treesketch.reconstruct(tree_cloud, up="y")
    assert y_up.up == "y" and y_up.up_reason != tree_model.up_reason


def test_bad_options_raise_options_error(tree_cloud):
    with pytest.raises(treesketch.OptionsError):
        treesketch.reconstruct(tree_cloud, up="x")
    with pytest.raises(ValueError):  # OptionsError is a ValueError
        treesketch.reconstruct(tree_cloud, unit_metres=-1)


def test_no_model_raises_the_cli_message(line_cloud_path, cli, tmp_path):
    code, _, message = run_cli(cli, "reconstruct", line_cloud_path, "--auto", "-o", tmp_path / "m.obj")
    assert code != 0 and "no mesh written" in message
    with pytest.raises(treesketch.DegenerateInputError) as e:
        treesketch.reconstruct(treesketch.read_cloud(str(line_cloud_path)))
    assert str(e.value) == message


def test_progress_is_reported(tree_cloud):
    calls = []
    treesketch.reconstruct(tree_cloud, progress=lambda done, total: calls.append((done, total)))
    assert len(calls) > 4
    assert all(0 <= d <= t for d, t in calls)


def test_an_exception_in_the_callback_stops_the_work_and_is_raised(tree_cloud):
    class Stop(Exception):
        pass

    calls = []

    def progress(done, total):
        calls.append(done)
        if len(calls) == 2:
            raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        treesketch.reconstruct(tree_cloud, progress=progress)
    assert len(calls) == 2  # no report after the exception


def test_the_gil_is_released_during_reconstruct(big_cloud):
    import threading
    import time

    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    start = time.perf_counter()
    treesketch.reconstruct(big_cloud)
    elapsed = time.perf_counter() - start
    done.set()
    t.join()
    during = [x for x in ticks if start < x < start + elapsed]
    # With the GIL held for the whole call the other thread could not tick during it.
    assert len(during) >= 5


def test_ctrl_c_stops_the_work(big_cloud):
    import _thread
    import threading
    import time

    cloud = big_cloud  # long enough to be interrupted
    start = time.perf_counter()
    treesketch.reconstruct(cloud)
    full = time.perf_counter() - start
    timer = threading.Timer(full / 10, _thread.interrupt_main)
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        treesketch.reconstruct(cloud)
    interrupted = time.perf_counter() - start
    timer.join()
    # Python raises a pending KeyboardInterrupt after a call that ignored it too: the call must
    # have stopped early (at the next report after the interrupt), not run to its end.
    assert interrupted < 0.6 * full, f"interrupted after {interrupted:.3f} s of {full:.3f} s"
