# The sketch path: the automatic model's sketch fitted again, edited, rebuilt incrementally; the
# same mesh as the CLI's `reconstruct --sketch`.
import numpy as np
import pytest

import treesketch
from conftest import run_cli


def test_the_model_sketch_rebuilds_the_model_mesh(tree_cloud, tree_model):
    rec = treesketch.fit(tree_cloud, tree_model.sketch)
    v, f = rec.mesh()
    mv, mf = tree_model.mesh()
    assert np.array_equal(f, mf) and np.array_equal(v, mv)
    sk = tree_model.sketch
    kept = [sk.node(i)["kept_radius"] is not None for i in sk.ids]
    assert np.array_equal(rec.fits["id"], sk.ids) and np.array_equal(rec.fits["kept"], kept)


def test_sketch_file_gives_the_cli_model(tree_cloud_path, tree_cloud, tree_model, cli, tmp_path):
    sketch_path = tmp_path / "s.json"
    tree_model.write(str(sketch_path))
    outputs = {"mesh": "cli.obj", "cylinders": "cli.csv", "qsm": "cli.txt", "metrics": "cli_metrics.json"}
    code, _, message = run_cli(cli, "reconstruct", tree_cloud_path, "--sketch", sketch_path, "--refit", "-o",
                               tmp_path / outputs["mesh"], "--cylinders", tmp_path / outputs["cylinders"], "--qsm",
                               tmp_path / outputs["qsm"], "--metrics", tmp_path / outputs["metrics"])
    assert code == 0, message
    sk = treesketch.read_sketch(str(sketch_path))
    kept = sum(sk.node(i)["kept_radius"] is not None for i in sk.ids)
    assert 0 < kept <= len(sk)
    assert sk.clear_kept_circles() == kept
    model = treesketch.fit(tree_cloud, sk).model()
    for kind, name in outputs.items():
        model.write(str(tmp_path / ("py_" + name)), kind=kind)
        assert (tmp_path / ("py_" + name)).read_bytes() == (tmp_path / name).read_bytes(), kind
    c = model.cylinders
    assert len(c["id"]) > 10 and c["measured"].any()


def test_a_sketch_with_no_fit_raises(tree_cloud):
    sk = treesketch.Sketch()
    root = sk.add_point_node(-1, [50, 50, 50], [0, 0, 1])  # far from every point
    sk.add_point_node(root, [50, 50, 51], [0, 0, 1])
    rec = treesketch.fit(tree_cloud, sk)
    with pytest.raises(treesketch.DegenerateInputError, match="no node could be fitted"):
        rec.model()
    with pytest.raises(treesketch.OptionsError, match="update"):
        treesketch.Reconstruction(tree_cloud).model()


def test_an_edit_refits_only_what_it_touches(tree_cloud, tree_model):
    sk = tree_model.sketch
    sk.clear_kept_circles()
    rec = treesketch.Reconstruction(tree_cloud)
    first = rec.update(sk)
    assert sorted(first) == sk.ids and rec.fit_count == len(sk)
    assert rec.update(sk) == []  # nothing changed
    fitted = dict(zip(rec.fits["id"].tolist(), rec.fits["status"]))
    leaf = next(i for i in sk.ids if i != sk.root and fitted[i] == "fitted")  # a node with a circle and a band
    node = sk.node(leaf)
    sk.move_node(leaf, node["point"] + [0.01, 0, 0], node["normal"])
    assert rec.update(sk) == [leaf]
    assert rec.fit_count == len(sk) + 1
    before = rec.mesh()[0].copy()
    sk.set_enabled(leaf, False)
    rec.update(sk)
    assert rec.fits["status"][list(rec.fits["id"]).index(leaf)] == "disabled"
    sk.set_enabled(leaf, True)
    rec.update(sk)
    sk.remove_node(leaf, with_subtree=True)
    rec.update(sk)
    assert len(rec.mesh()[0]) < len(before)


def test_kept_circles_are_used_not_fitted(tree_cloud):
    sk = treesketch.Sketch()
    root = sk.add_point_node(-1, [0, 0, 0.5], [0, 0, 1])
    child = sk.add_point_node(root, [0, 0, 1.5], [0, 0, 1])
    sk.set_kept_circle(root, [0, 0, 0.5], 0.2)
    sk.set_kept_circle(child, [0, 0, 1.5], 0.1)
    rec = treesketch.fit(tree_cloud, sk)
    fits = rec.fits
    assert fits["kept"].all() and np.allclose(fits["radius"], [0.2, 0.1])
    sk.set_kept_circle(child, None)
    assert sk.node(child)["kept_radius"] is None


def test_bad_sketches_raise(tmp_path, tree_cloud):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "treesketch-sketch", "version": 1, "nodes": [')
    with pytest.raises(treesketch.InputError, match="bad.json"):
        treesketch.read_sketch(str(bad))
    sk = treesketch.Sketch()
    with pytest.raises(treesketch.OptionsError):
        sk.node(3)
    with pytest.raises(treesketch.OptionsError, match="normal"):
        sk.add_point_node(-1, [0, 0, 0], [0, 0, np.nan])
