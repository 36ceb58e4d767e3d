# scan and compare: the virtual scanner's cloud and the surface distances, with known answers.
import numpy as np
import pytest

import treesketch


def test_scan_hits_the_tree(tree_mesh):
    cloud = treesketch.scan(tree_mesh, subdivisions=4, up="z", record_mesh=True)
    v = tree_mesh[0]
    assert len(cloud) > 100 and cloud.up == "z"
    assert (cloud.xyz >= v.min(axis=0) - 1e-6).all() and (cloud.xyz <= v.max(axis=0) + 1e-6).all()
    assert "mesh_id" in cloud.attributes and (cloud.mesh_id == 0).all()


def test_scan_is_deterministic_and_seeded(tree_mesh):
    a = treesketch.scan(tree_mesh, subdivisions=4, seed=5)
    b = treesketch.scan(tree_mesh, subdivisions=4, seed=5)
    c = treesketch.scan(tree_mesh, subdivisions=4, seed=6)
    assert np.array_equal(a.xyz, b.xyz)
    assert not np.array_equal(a.xyz, c.xyz) if len(a) == len(c) else True


def test_tls_scan_records_stations(tree_mesh):
    cloud = treesketch.scan([tree_mesh], pattern="tls", up="z", step_deg=1.0)
    assert set(np.unique(cloud.station)) <= {0, 1, 2, 3} and len(np.unique(cloud.station)) > 1


def test_compare_a_mesh_with_itself_and_a_shifted_copy(tree_mesh):
    same = treesketch.compare(tree_mesh, tree_mesh)
    assert same["hausdorff"] == pytest.approx(0, abs=1e-9)
    v, f = tree_mesh
    shift = 0.05
    moved = treesketch.compare(tree_mesh, (v + [shift, 0, 0], f), one_way=True)
    assert set(moved) == {"forward"}
    assert moved["forward"]["max"] <= shift + 1e-9 and moved["forward"]["max"] > 0.5 * shift


def test_compare_a_mesh_with_its_scan(tree_mesh):
    cloud = treesketch.scan(tree_mesh, subdivisions=4, noise=0.0)
    r = treesketch.compare(tree_mesh, cloud)
    assert r["backward"]["max"] < 1e-6  # every scanned point lies on the mesh


def test_bad_meshes_raise(tree_mesh):
    v, f = tree_mesh
    with pytest.raises(treesketch.OptionsError, match="vertex"):
        treesketch.compare((v, f + len(v)), tree_mesh)
    with pytest.raises(treesketch.OptionsError, match="pair"):
        treesketch.scan([v])
    flat = (np.zeros((3, 3)), np.array([[0, 1, 2]]))
    with pytest.raises(treesketch.DegenerateInputError, match="zero area"):
        treesketch.scan(flat)
    with pytest.raises(treesketch.OptionsError, match="pattern"):
        treesketch.scan(tree_mesh, pattern="cone")
