"""The camera maps world units (y up) to pixels (y down) and back, on floats and arrays."""

import doctest

import numpy as np
import pytest

from engine.render import camera as camera_module
from engine.render.camera import Camera


def test_doctests_pass():
    assert doctest.testmod(camera_module).failed == 0


def test_maps_world_to_pixels_with_y_flipped():
    cam = Camera(scale=50.0, origin=(40.0, 300.0))
    assert cam.to_px(0.0, 0.0) == (40.0, 300.0)
    assert cam.to_px(1.0, 0.0) == (90.0, 300.0)
    assert cam.to_px(0.0, 1.0) == (40.0, 250.0)  # up in the world is up on the screen


def test_inverse_round_trips():
    cam = Camera(scale=37.5, origin=(12.0, 200.0))
    x, y = cam.to_world(*cam.to_px(3.25, -1.5))
    assert (x, y) == pytest.approx((3.25, -1.5))


def test_vectorised_on_numpy_arrays():
    cam = Camera(scale=10.0, origin=(5.0, 100.0))
    xy = np.array([[0.0, 0.0], [1.0, 2.0], [-3.0, 0.5]])
    px = cam.points(xy)
    expected = np.array([cam.to_px(x, y) for x, y in xy])
    np.testing.assert_allclose(px, expected)
    xs, ys = cam.to_px(xy[:, 0], xy[:, 1])
    np.testing.assert_allclose(np.column_stack((xs, ys)), expected)


def test_point_rounds_halves_up_and_accepts_floats_and_pairs():
    cam = Camera(scale=1.0, origin=(0.0, 10.0))
    assert cam.point(2.5) == (3, 10)
    assert cam.point((0.5, 0.5)) == (1, 10)  # py = 9.5 rounds to 10


def test_fit_centres_the_world_box_and_keeps_aspect():
    cam = Camera.fit((0.0, 0.0, 10.0, 5.0), (0, 0, 200, 200))
    assert cam.scale == 20.0
    # The box's centre (5, 2.5) lands on the rect's centre.
    assert cam.to_px(5.0, 2.5) == pytest.approx((100.0, 100.0))


@pytest.mark.parametrize("scale", [0.0, -1.0, float("nan"), float("inf")])
def test_rejects_bad_scale_naming_it(scale):
    with pytest.raises(ValueError, match="scale"):
        Camera(scale)
