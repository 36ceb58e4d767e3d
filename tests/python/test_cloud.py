# Clouds: NumPy in and out, views that keep their cloud alive, attributes, bad input.
import gc
import weakref

import numpy as np
import pytest

import treesketch
from conftest import run_cli


def test_from_numpy_round_trip_is_exact():
    rng = np.random.default_rng(1)
    xyz = rng.normal(size=(1000, 3)) * [1e5, 1e5, 1e2] + [5e5, 5e6, 250]  # projected coordinates
    c = treesketch.Cloud.from_numpy(xyz)
    assert len(c) == 1000
    assert c.xyz.shape == (1000, 3) and c.xyz.dtype == np.float64
    assert np.array_equal(c.xyz, xyz)
    assert not np.shares_memory(c.xyz, xyz)  # the cloud owns its copy


def test_from_numpy_takes_float32_and_non_contiguous_arrays():
    xyz = np.arange(30, dtype=np.float32).reshape(10, 3)
    assert np.array_equal(treesketch.Cloud.from_numpy(xyz).xyz, xyz.astype(np.float64))
    wide = np.arange(60, dtype=np.float64).reshape(10, 6)
    assert np.array_equal(treesketch.Cloud.from_numpy(wide[:, ::2]).xyz, wide[:, ::2])


def test_xyz_is_a_view_of_the_cloud_and_keeps_it_alive():
    c = treesketch.Cloud.from_numpy(np.zeros((5, 3)))
    a = c.xyz
    assert np.shares_memory(a, c.xyz)  # no copy: both views of the same storage
    a[2, 1] = 7.0
    assert c.xyz[2, 1] == 7.0
    ref = weakref.ref(c)
    del c
    gc.collect()
    assert ref() is not None  # the view holds the cloud
    assert a[2, 1] == 7.0
    del a
    gc.collect()
    assert ref() is None


def test_attributes_from_numpy_are_kept():
    n = 20
    rng = np.random.default_rng(2)
    xyz = rng.uniform(size=(n, 3))
    intensity = rng.uniform(0, 1000, size=n).astype(np.float32)
    classification = rng.integers(0, 20, size=n).astype(np.uint8)
    color = rng.integers(0, 256, size=(n, 3)).astype(np.uint8)
    c = treesketch.Cloud.from_numpy(xyz, up="y", intensity=intensity, classification=classification, color=color)
    assert c.attributes == ["intensity", "classification", "color"]
    assert np.array_equal(c.intensity, intensity) and c.intensity.dtype == np.float32
    assert np.array_equal(c.classification, classification)
    assert np.array_equal(c.color, color) and c.color.shape == (n, 3)
    assert c.up == "y"


def test_positions_and_up_round_trip_through_a_ply_file(tmp_path):
    xyz = np.random.default_rng(3).uniform(size=(50, 3)) + [5e5, 5e6, 250]
    path = tmp_path / "c.ply"
    treesketch.Cloud.from_numpy(xyz, up="y").write(str(path))
    back = treesketch.read_cloud(str(path))
    assert np.array_equal(back.xyz, xyz) and back.up == "y"


def test_the_attributes_a_file_has_are_read(tmp_path):
    path = tmp_path / "attr.ply"
    rows = [(0, 0, 0, 10.5, 255, 0, 0, 2), (1, 0, 0, 20.5, 0, 255, 0, 5), (0, 1, 0, 30.5, 0, 0, 255, 2),
            (0, 0, 1, 40.5, 9, 9, 9, 5)]
    header = ["ply", "format ascii 1.0", f"element vertex {len(rows)}", "property float x", "property float y",
              "property float z", "property float intensity", "property uchar red", "property uchar green",
              "property uchar blue", "property uchar classification", "end_header"]
    path.write_text("\n".join(header + [" ".join(map(str, r)) for r in rows]) + "\n")
    c = treesketch.read_cloud(str(path))
    assert set(c.attributes) == {"intensity", "color", "classification"}
    assert np.array_equal(c.intensity, [10.5, 20.5, 30.5, 40.5])
    assert np.array_equal(c.color[1], [0, 255, 0]) and np.array_equal(c.classification, [2, 5, 2, 5])


def test_a_cloud_without_attributes_says_so():
    c = treesketch.Cloud.from_numpy(np.zeros((4, 3)))
    assert c.attributes == [] and c.intensity is None and c.color is None and c.up is None


def test_empty_array_gives_an_empty_cloud():
    c = treesketch.Cloud.from_numpy(np.zeros((0, 3)))
    assert len(c) == 0 and c.xyz.shape == (0, 3)


@pytest.mark.parametrize("bad", [np.zeros((4, 2)), np.zeros(12), np.zeros((2, 3, 2))])
def test_from_numpy_rejects_other_shapes(bad):
    with pytest.raises(treesketch.OptionsError, match="N x 3"):
        treesketch.Cloud.from_numpy(bad)


@pytest.mark.parametrize("value", [np.nan, np.inf])
def test_from_numpy_rejects_nan_and_inf_naming_the_row(value):
    xyz = np.zeros((6, 3))
    xyz[4, 2] = value
    with pytest.raises(treesketch.InputError, match="row 4"):
        treesketch.Cloud.from_numpy(xyz)


def test_from_numpy_rejects_attributes_of_another_length():
    with pytest.raises(ValueError, match="intensity"):
        treesketch.Cloud.from_numpy(np.zeros((4, 3)), intensity=np.zeros(3))


def test_read_errors_carry_the_cli_message(tmp_path, cli):
    cases = {"missing.xyz": None, "bad.xyz": "1 2 3\n4 5 x\n", "few.xyz": "1 2 3\n", "nan.xyz": "1 2 3\n" * 4 + "nan 1 2\n",
             "c.unknown": "1 2 3\n"}
    for name, text in cases.items():
        path = tmp_path / name
        if text is not None:
            path.write_text(text)
        code, _, message = run_cli(cli, "reconstruct", path, "--auto", "-o", tmp_path / "m.obj")
        assert code != 0
        with pytest.raises(treesketch.InputError) as e:
            treesketch.read_cloud(str(path))
        assert str(e.value) == message
        assert isinstance(e.value, treesketch.Error)
