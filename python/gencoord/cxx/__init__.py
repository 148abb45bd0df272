# SPDX-License-Identifier: BSD-3-Clause
"""The C++ backend: expressions printed as C++ (printer.py), kernels written as statements and
parts (kernel_writer.py, kernel_code.py, lvalues.py), their signatures and storage types,
long lines wrapped, the names a model may not use (reserved_names.py, cxx_macros.txt), and the
Jinja2 templates (templates/) rendered into headers (render.py, template_views.py)."""
