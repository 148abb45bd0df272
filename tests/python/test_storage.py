# SPDX-License-Identifier: BSD-3-Clause
"""The Eigen types of a model's vectors and matrices: fixed-size up to Eigen's stack limit
(16,384 doubles), gencoord::HeapMatrix beyond (gencoord/cxx/storage.py)."""
import unittest

from gencoord.cxx.storage import FIXED_SIZE_MAX_ENTRIES, model_types, needs_heap_matrix


class StorageTest(unittest.TestCase):
    def test_limit_is_eigens_128_kib_of_doubles(self):
        self.assertEqual(FIXED_SIZE_MAX_ENTRIES * 8, 128 * 1024)

    def test_mass_matrix_leaves_the_stack_past_128_coordinates(self):
        at_limit = model_types(128, 128, 2)     # Mt: 16,384 entries
        past = model_types(129, 129, 2)         # 16,641
        self.assertEqual(at_limit["QMatrix"], "Eigen::Matrix<Scalar, nq, nq>")
        self.assertEqual(past["QMatrix"], "gencoord::HeapMatrix<Scalar, nq, nq>")
        self.assertEqual(past["VMatrix"], "gencoord::HeapMatrix<Scalar, nv, nv>")
        self.assertEqual(past["QVector"], "Eigen::Matrix<Scalar, nq, 1>")
        self.assertFalse(needs_heap_matrix(at_limit))
        self.assertTrue(needs_heap_matrix(past))

    def test_speeds_size_their_own_types(self):
        robot = model_types(19, 18, 300)  # a floating quadruped: q has a quaternion
        self.assertEqual(robot["VQMatrix"], "Eigen::Matrix<Scalar, nv, nq>")
        self.assertEqual(robot["XJacobian"], "Eigen::Matrix<Scalar, nx, nv>")

    def test_jacobian_goes_first_when_nx_exceeds_nq(self):
        chain = model_types(100, 100, 200)      # J: 20,000 entries, Mt: 10,000
        self.assertEqual(chain["XJacobian"], "gencoord::HeapMatrix<Scalar, nx, nv>")
        self.assertEqual(chain["QMatrix"], "Eigen::Matrix<Scalar, nq, nq>")
        self.assertEqual(chain["XVector"], "Eigen::Matrix<Scalar, nx, 1>")


if __name__ == "__main__":
    unittest.main()
