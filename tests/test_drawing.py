"""The drawing module (pycram_cli/drawing.py): the maps' lines, dots, shapes and text, drawn with Pillow."""
from __future__ import annotations

import numpy as np

from pycram_cli.drawing import Picture, darker

RED = (220, 60, 50)


def test_a_picture_starts_in_its_background_and_gives_rows_by_columns():
    rgb = Picture(40, 30, (10, 20, 30)).rgb()
    assert rgb.shape == (30, 40, 3) and rgb.dtype == np.uint8
    assert (rgb == (10, 20, 30)).all()


def test_a_picture_drawn_over_an_array_leaves_the_array_as_it_was():
    under = np.full((20, 20, 3), 200, dtype=np.uint8)
    picture = Picture.of(under)
    picture.dots(np.array([[10, 10]]), RED, radius=2)
    assert (under == 200).all()
    drawn = picture.rgb()
    assert tuple(drawn[10, 10]) == RED and tuple(drawn[10, 13]) == (200, 200, 200)


def test_dots_are_squares_of_side_twice_the_radius_and_one():
    picture = Picture(20, 20)
    picture.dots(np.array([[5, 5], [14, 14]]), RED, radius=1)
    drawn = picture.rgb()
    red = np.all(drawn == RED, axis=-1)
    assert red.sum() == 2 * 9 and red[4:7, 4:7].all() and red[13:16, 13:16].all()


def test_translucent_shapes_blend_with_what_is_under_them():
    picture = Picture(10, 10, (255, 255, 255))
    picture.rectangle((0, 0), (9, 9), fill=(0, 0, 0), alpha=0.5)
    value = int(picture.rgb()[5, 5, 0])
    assert 120 <= value <= 135


def test_lines_and_outlines_touch_the_pixels_between_their_ends_only():
    picture = Picture(30, 30)
    picture.line([(2, 15), (27, 15)], RED, width=1)
    picture.rectangle((5, 5), (10, 10), outline=(0, 0, 255))
    drawn = picture.rgb()
    assert all(tuple(drawn[15, x]) == RED for x in range(2, 28)) and tuple(drawn[14, 15]) == (255, 255, 255)
    assert tuple(drawn[5, 7]) == (0, 0, 255) and tuple(drawn[7, 7]) == (255, 255, 255)


def test_text_is_drawn_in_the_default_font_and_measured():
    picture = Picture(200, 30)
    picture.text((2, 2), "3 found", (0, 0, 0))
    dark = np.all(picture.rgb() < 128, axis=-1)
    assert dark.any() and not dark[:, 150:].any()
    assert 0 < picture.text_width("3 found") < picture.text_width("3 found, 2 blocked")


def test_the_same_drawing_gives_the_same_pixels():
    def draw() -> np.ndarray:
        picture = Picture(60, 40)
        picture.circle((20, 20), 6, fill=RED, outline=darker(RED))
        picture.polygon([(40, 10), (50, 30), (30, 30)], fill=(0, 150, 0))
        picture.text((2, 2), "x target", (20, 20, 20))
        return picture.rgb()

    assert np.array_equal(draw(), draw())


def test_darker_scales_each_channel():
    assert darker((200, 100, 0)) == (110, 55, 0)
