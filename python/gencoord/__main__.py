"""`python -m gencoord ...`: the gencoord command."""

from gencoord.commands import gencoord

gencoord()
