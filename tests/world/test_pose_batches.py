"""Poses for many at once give the numbers the one-at-a-time functions give, bitwise (collision-checked paths rely on
it to answer as before)."""
from __future__ import annotations

import numpy as np

from pycram_cli.world.pose import quat_to_matrix, quats_to_matrices


def test_quaternions_to_matrices_at_once_are_the_same_numbers():
    rng = np.random.default_rng(20261126)
    for count in (0, 1, 3, 7, 12):
        quats = rng.normal(size=(count, 4))
        quats /= np.linalg.norm(quats, axis=1)[:, None] if count else 1.0
        rows = [tuple(float(v) for v in q) for q in quats]
        one_by_one = np.array([quat_to_matrix(q) for q in rows]).reshape(-1, 3, 3)
        assert quats_to_matrices(np.array(rows, dtype=float).reshape(-1, 4)).tobytes() == one_by_one.tobytes()
