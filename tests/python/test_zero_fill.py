# SPDX-License-Identifier: BSD-3-Clause
"""Matrices with many zero entries are set to zero at once (gencoord/cxx/kernel_writer.py): the
chain's J, whose entries above the diagonal of each particle's rows are zero, gets one
setZero() and an assignment per nonzero entry only, in whole kernels and in parts."""
import re
import unittest

from gencoord.generate.stages import generate
from gencoord.options import GenerateOptions

from .support import REPO

CHAIN = str(REPO / "models" / "n_link_chain.py")


def _kernel(header: str, signature: str) -> str:
    start = header.index(signature)
    return header[start:header.index("\n  }\n", start)]


class ZeroFillTest(unittest.TestCase):
    def test_jacobian_assigns_only_its_nonzeros(self):
        n = 5
        header = generate(CHAIN, {"n": str(n)}).header
        jacobian = _kernel(header, "static XJacobian<Scalar> jacobian(")
        self.assertEqual(jacobian.count("result.setZero();"), 1)
        assigned = re.findall(r"result\((\d+), (\d+)\) = (.*);", jacobian)
        # particle k (rows 2k, 2k + 1) moves with theta_1 .. theta_(k+1) only
        self.assertEqual(sorted((int(i), int(j)) for i, j, _ in assigned),
                         [(i, j) for i in range(2 * n) for j in range(i // 2 + 1)])
        self.assertNotIn("Scalar(0)", [code for *_, code in assigned])
        self.assertGreaterEqual(2 * n * n - len(assigned), GenerateOptions.zero_fill_min)

    def test_parts_write_nonzeros_after_the_kernel_zeroes(self):
        header = generate(CHAIN, {"n": "5"}, GenerateOptions(max_part_statements=4)).header
        jacobian = _kernel(header, "static XJacobian<Scalar> jacobian(")
        calls = jacobian.index("jacobian_part0<Scalar>(")
        self.assertLess(jacobian.index("result.setZero();"), calls)
        parts = header[header.index("jacobian_part0("):
                       header.index("static XJacobian<Scalar> jacobian(")]
        self.assertIn("result_data[", parts)
        self.assertNotIn("= Scalar(0);", parts)

    def test_few_zeros_are_assigned(self):
        header = generate(CHAIN, {"n": "2"}).header
        jacobian = _kernel(header, "static XJacobian<Scalar> jacobian(")
        self.assertNotIn("setZero", jacobian)
        self.assertIn("result(0, 1) = Scalar(0);", jacobian)


if __name__ == "__main__":
    unittest.main()
