# The Python path gives the CLI's cylinder table, metrics and model fit on every single-tree cloud
# of the shared real scans (skipped when ../shared is absent).
import json

import numpy as np
import pytest

import treesketch
from conftest import run_cli, shared_data_dir

REAL = shared_data_dir() / "real"
# The single trees of real/README.md (plots are not one tree) and whether they were scanned in leaf.
TREES = [
    ("rtwig_cloud.txt", False),
    ("archi_Tree_2_point_cloud.las", False),
    ("adtree_tree7.xyz", False),
    ("adtree_tree1.xyz", False),
    ("adtree_Lille_11.xyz", False),
    ("voxr_Tree_t0.asc", False),
    ("voxr_Tree_t1.asc", False),
    ("plantscan3d_A3B4.asc", False),
    ("pctm_ahn_filtered_tree_121913_487434.las", False),
    ("rtls_pc_tree.txt", True),
    ("itsme_tree_1_pc.txt", True),
    ("pytlidar_tree_1.las", True),
    ("treels_spruce.laz", True),
    ("treels_spruce_decoded.xyz", True),
]


@pytest.mark.parametrize("name,leaf_on", TREES, ids=[t[0] for t in TREES])
def test_python_gives_the_cli_model(name, leaf_on, cli, tmp_path):
    path = REAL / name
    if not path.exists():
        pytest.skip(f"{path} absent")
    cloud = treesketch.read_cloud(str(path))  # every format there is read: a failure is a failure

    args = ["reconstruct", path, "--auto", "-o", tmp_path / "m.obj", "--cylinders", tmp_path / "c.csv",
            "--qsm", tmp_path / "q.txt", "--metrics", tmp_path / "metrics.json", "--report", tmp_path / "r.json"]
    code, out, message = run_cli(cli, *args, *(["--leaf-on"] if leaf_on else []))
    model = None
    try:
        model = treesketch.reconstruct(cloud, leaf_on=leaf_on)
    except treesketch.DegenerateInputError as e:
        assert code != 0 and str(e) == message  # the same failure, the same words
        return
    assert code == 0, message

    # The cylinder table: byte for byte, and the arrays hold its values.
    model.write(str(tmp_path / "py.csv"))
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "c.csv").read_bytes()
    table = np.genfromtxt(tmp_path / "c.csv", delimiter=",", names=True)
    c = model.cylinders
    assert np.array_equal(np.atleast_1d(table["id"]), c["id"])
    assert np.array_equal(np.atleast_1d(table["parent"]), c["parent"])
    assert np.array_equal(np.atleast_1d(table["branch_order"]), c["branch_order"])
    for key, cols in (("start", ("start_x", "start_y", "start_z")), ("end", ("end_x", "end_y", "end_z"))):
        cli_xyz = np.column_stack([np.atleast_1d(table[k]) for k in cols])
        assert np.allclose(cli_xyz, c[key], rtol=1e-8, atol=1e-12)
    for key in ("radius", "length", "start_radius"):
        assert np.allclose(np.atleast_1d(table[key]), c[key], rtol=1e-8, atol=1e-12)
    model.write(str(tmp_path / "py.txt"))
    assert (tmp_path / "py.txt").read_bytes() == (tmp_path / "q.txt").read_bytes()

    # The mesh, the metrics and the model fit of the report.
    model.write(str(tmp_path / "py.obj"))
    assert (tmp_path / "py.obj").read_bytes() == (tmp_path / "m.obj").read_bytes()
    model.write(str(tmp_path / "py_metrics.json"), kind="metrics")
    assert (tmp_path / "py_metrics.json").read_bytes() == (tmp_path / "metrics.json").read_bytes()
    report = json.loads((tmp_path / "r.json").read_text())
    assert model.metrics() == report["metrics"]
    fit = model.fit_report(cloud)
    for key in ("fit", "figures", "measuredVolumeShare"):
        assert fit[key] == report["model"][key], key
    model.write(str(tmp_path / "py_r.json"), kind="report", cloud=cloud)
    py_report = json.loads((tmp_path / "py_r.json").read_text())
    assert py_report["model"] == report["model"] and py_report["metrics"] == report["metrics"]
    assert model.up == report["up"] and model.up_reason == report["upReason"]
    s = model.summary
    assert (s["skeleton_nodes"], s["forks"], s["vertices"]) == (report["skeletonNodes"], report["forks"],
                                                                  report["vertices"])
