# treesketch.classify and reconstruct(wood_only=True): the wood/leaf classification from Python,
# the same as `treesketch classify` and `reconstruct --auto --wood-only`.
import numpy as np
import pytest

import treesketch
from conftest import run_cli


@pytest.fixture(scope="module")
def leafy(tree_mesh):
    """The sparse tree's wood scanned, with a crown of scattered points standing in for leaves:
    (cloud, number of wood points first)."""
    wood = treesketch.scan(tree_mesh, subdivisions=7, up="z", seed=5).xyz
    lo, hi = wood.min(axis=0), wood.max(axis=0)
    rng = np.random.default_rng(7)
    crown = rng.uniform([lo[0], lo[1], lo[2] + 0.5 * (hi[2] - lo[2])], hi, size=(len(wood) // 2, 3))
    return treesketch.Cloud.from_numpy(np.vstack([wood, crown]), up="z"), len(wood)


def test_classify_gives_per_point_arrays(leafy):
    cloud, n_wood = leafy
    c = treesketch.classify(cloud)
    n = len(cloud.xyz)
    p, wood, codes = c["wood_probability"], c["wood"], c["classification"]
    assert p.shape == wood.shape == codes.shape == (n,)
    assert p.dtype == np.float32 and wood.dtype == np.bool_ and codes.dtype == np.uint8
    assert ((p >= 0) & (p <= 1)).all()
    assert np.array_equal(codes == 64, wood) and np.array_equal(codes == 65, ~wood)
    assert c["wood_points"] == wood.sum()
    assert 0 < c["threshold"] < 1
    # The branches score above the scattered crown, and the graph step never makes a point wood
    # below the threshold.
    assert p[:n_wood].mean() > p[n_wood:].mean() + 0.2
    assert wood[:n_wood].mean() > wood[n_wood:].mean()
    assert (p[wood] >= c["threshold"]).all()


def test_classify_threshold_and_bad_input(leafy):
    cloud, _ = leafy
    strict = treesketch.classify(cloud, threshold=0.99)
    loose = treesketch.classify(cloud, threshold=0.05)
    assert strict["wood_points"] < loose["wood_points"]
    with pytest.raises(treesketch.OptionsError):
        treesketch.classify(cloud, threshold=2.0)
    tiny = treesketch.Cloud.from_numpy(np.random.default_rng(1).uniform(size=(10, 3)))
    with pytest.raises(treesketch.DegenerateInputError):
        treesketch.classify(tiny)


def test_wood_only_is_the_cli_model(leafy, cli, tmp_path):
    cloud, _ = leafy
    path = tmp_path / "leafy.xyz"
    cloud.write(str(path))
    code, _, message = run_cli(cli, "reconstruct", path, "--auto", "--wood-only", "--up", "z", "-o", tmp_path / "m.obj",
                               "--cylinders", tmp_path / "c.csv")
    assert code == 0, message
    model = treesketch.reconstruct(treesketch.read_cloud(str(path)), wood_only=True, up="z")
    model.write(str(tmp_path / "py.csv"))
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "c.csv").read_bytes()
    n = len(cloud.xyz)
    assert 0 < model.summary["wood_points"] < n
    every = treesketch.reconstruct(treesketch.read_cloud(str(path)), leaf_on=True, up="z")
    assert every.summary["wood_points"] == 0
    assert len(model.cylinders["id"]) < len(every.cylinders["id"])  # no tubes in the scattered crown
