"""mcws.boundary(path, tiles=N) against mcws_boundary --tiles N on the same file, and against the
boundary found in memory (the tiled run's promise: the same points)."""

import numpy as np
import pytest

import mcws
from conftest import run_tool


def xyz(points):
    return np.stack([points["x"], points["y"], points["z"]], axis=1)


@pytest.fixture(scope="module")
def clouds(tmp_path_factory):
    """A disk and a ball of 20000 points, written as binary PCD."""
    folder = tmp_path_factory.mktemp("tiles")
    out = {}
    for shape, seed in (("disk", 2), ("ball", 3)):
        points = mcws.sample_shape(shape, 20000, seed=seed)
        path = folder / (shape + ".pcd")
        mcws.write_pcd(path, points)
        out[shape] = points, path
    return out


@pytest.mark.parametrize("shape,plane,tiles,settings,flags", [
    ("ball", None, 3, {}, []),
    ("ball", None, 5, {"radius": 0.2}, ["--radius", "0.2"]),
    ("disk", "xy", 4, {"hull_depth": 0}, ["--hull-depth", "0"]),
    ("disk", "xy", 2, {"adaptive": 12, "hull_depth": 0}, ["--adaptive", "12", "--hull-depth", "0"]),
])
def test_tiled_boundary_is_mcws_boundary_tiles(clouds, tmp_path, shape, plane, tiles, settings,
                                               flags):
    points, path = clouds[shape]
    out = tmp_path / "boundary.pcd"
    plane_flags = ["--plane", plane] if plane else []
    run_tool("boundary", "--input", path, "--output", out, "--tiles", tiles, *plane_flags, *flags)
    seen = []
    mask = mcws.boundary(path, plane, tiles=tiles, progress=lambda done, all: seen.append(
        (done, all)), **settings)
    assert mask.dtype == np.bool_ and mask.shape == (len(points),)
    # The tool writes the boundary points in the file's order: the mask's points, row for row.
    written = xyz(mcws.read_pcd(out))
    assert 0 < mask.sum() == len(written) < len(points)
    np.testing.assert_array_equal(xyz(points[mask]), written)
    # The same points as the boundary found in memory, from the array or from the file.
    np.testing.assert_array_equal(mask, mcws.boundary(points, plane, **settings))
    np.testing.assert_array_equal(mask, mcws.boundary(path, plane, **settings))
    assert seen[-1] == (tiles, tiles) and len(seen) == tiles


def test_tiled_boundary_errors(clouds, tmp_path):
    points, path = clouds["disk"]
    with pytest.raises(mcws.UsageError, match=r"^tiles: the cloud is read from a binary PCD"):
        mcws.boundary(points, "xy", tiles=2, hull_depth=0)
    with pytest.raises(mcws.UsageError, match=r"^tiles works with method 'orthant'$"):
        mcws.boundary(path, "xy", tiles=2, method="grid")
    with pytest.raises(mcws.UsageError, match=r"^auto_radius needs the whole cloud's spacing"):
        mcws.boundary(path, "xy", tiles=2, auto_radius=2, hull_depth=0)
    with pytest.raises(mcws.UsageError, match=r"^tiles: the hull-depth stage .*hull_depth=0"):
        mcws.boundary(path, "xy", tiles=2)
    with pytest.raises(mcws.UsageError, match=r"^tiles: 0 is not in 1 \.\. 100000$"):
        mcws.boundary(path, "xy", tiles=0, hull_depth=0)
    with pytest.raises(mcws.UsageError, match=r"^progress: applies with tiles"):
        mcws.boundary(points, "xy", progress=True)
    ascii_file = tmp_path / "ascii.pcd"
    ascii_file.write_text("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                          "COUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\n"
                          "DATA ascii\n0 0 0\n")
    with pytest.raises(mcws.Error, match=str(ascii_file)):
        mcws.boundary(ascii_file, tiles=2)
