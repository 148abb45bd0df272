# SPDX-License-Identifier: BSD-3-Clause
"""`python -m gencoord ...`: the gencoord command."""

from gencoord.commands import gencoord

gencoord()
