"""mcws.Error and mcws.UsageError: the classes, and the docstrings every public name carries."""

import pytest

import mcws


def test_error_classes():
    assert issubclass(mcws.Error, RuntimeError)
    assert issubclass(mcws.UsageError, ValueError)
    assert issubclass(mcws.UsageError, mcws.Error)  # `except mcws.Error` catches both
    assert not issubclass(mcws.Error, ValueError)
    assert mcws.Error.__module__ == "mcws" and mcws.UsageError.__module__ == "mcws"
    with pytest.raises(mcws.Error, match="^shape: "):
        mcws.sample_shape("cube", 1)  # a usage error caught as mcws.Error


@pytest.mark.parametrize("name", mcws.__all__)
def test_every_public_name_has_a_docstring_with_units_where_numbers_come_back(name):
    doc = getattr(mcws, name).__doc__
    assert doc and len(doc) > 40
    if name in ("sample", "sample_shape", "read_pcd", "write_pcd", "boundary", "measure", "Robot"):
        assert "unit" in doc


def test_robot_methods_have_docstrings_naming_units():
    for method in ("fk", "jacobian", "ik"):
        doc = getattr(mcws.Robot, method).__doc__
        assert "length unit" in doc or "length_unit" in doc, method
        assert "Raises" in doc, method


def test_messages_name_the_argument_not_a_tool_flag(ta1400):
    too_many = 2**62
    with pytest.raises(mcws.UsageError, match=rf"^n: {too_many} samples are more than an array "):
        mcws.sample(ta1400, too_many)
    with pytest.raises(mcws.UsageError, match=rf"^n: {too_many} samples are more than an array "):
        mcws.sample_shape("disk", too_many)
    # 1e-9 mm voxels: the TA1400's reach (~1.4 m) is beyond the grid's +-1048576 voxel indices.
    with pytest.raises(mcws.UsageError,
                       match=r"^resolution: reachability map: .* give a coarser resolution$"):
        mcws.reach_map(ta1400, 1e-9, 10)
    points = mcws.sample(ta1400, 2000, seed=1)
    with pytest.raises(mcws.UsageError, match=r"^adaptive: 2.5 is not a whole number"):
        mcws.boundary(points, "xz", adaptive=2.5)
