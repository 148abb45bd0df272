# SPDX-License-Identifier: BSD-3-Clause
"""`gencoord sweep FILE`: an ensemble of runs of one model, described by a TOML file, expanded
into a table of samples, run by the model's sweep program under MPI and recorded in one HDF5
file (docs/sweep.md)."""
