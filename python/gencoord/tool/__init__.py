# SPDX-License-Identifier: BSD-3-Clause
"""The `gencoord` command: generation, and programs built and cached per model file.

`gencoord generate` is the generator (gencoord/generate/cli.py). `gencoord simulate` and
`gencoord crosscheck` generate a model, compile one of the drivers (drivers/) for it against the
runtime into a per-user cache keyed by the model's content and options, and run it;
`gencoord info` describes a model file without building anything.
"""
