# SPDX-License-Identifier: BSD-3-Clause
"""The browser viewer: a trajectory as one self-contained HTML page, and headless Chromium."""
