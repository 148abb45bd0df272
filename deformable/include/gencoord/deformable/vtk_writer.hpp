// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file vtk_writer.hpp
/// ParaView output: each frame of a mass-spring object as a VTK XML unstructured grid (.vtu,
/// ASCII), and a .pvd collection that lists the frames with their times (File > Open the .pvd
/// in ParaView plays the run).
///
/// A .vtu holds one piece:
///  - points: the nodes as 3D points (2D padded with z = 0, 1D with y = z = 0);
///  - cells: every spring as a VTK_LINE (type 3), in the order of s.springs and broken ones
///    included, so that cell k is spring k in every frame; then, when a mesh is given, every
///    element as a VTK_TRIANGLE (5) or VTK_TETRA (10), in the mesh's order, its corners
///    ordered so that it is positively oriented in the rest shape (VTK's convention);
///  - point data: velocity (3 components, padded like the points), mass, pinned (0 or 1);
///  - cell data: kind (0 spring, 1 element); strain, for a spring (l - L) / L with its current
///    rest length L, for an element (A - A0) / A0, the relative change of its area or volume
///    from the mesh's rest shape; broken (0 or 1), for an element 1 when a spring along one of
///    its edges is broken;
///  - field data TimeValue: s.t.
/// Numbers are written in the shortest form that reads back to the same double, so the same
/// state gives the same bytes. Every file is written under a temporary name (the path plus
/// ".tmp") and renamed when complete, so no half-written file is left under its name.

#include <string>
#include <vector>

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable {

/// Writes the state of `s` to the .vtu file `path`. `mesh`, if not null, must be the mesh `s`
/// was made from (same nodes). \throws gencoord::OutputError naming the path if the file
/// cannot be written; std::invalid_argument if the mesh does not fit `s`.
template <int Dim>
void write_vtu(const std::string& path, const MassSpringSystem<Dim>& s,
               const SimplexMesh<Dim>* mesh = nullptr);

/// One frame of a .pvd collection: its time (s) and its file, relative to the .pvd's folder.
struct PvdFrame {
  double time = 0.0;
  std::string file;
};

/// Writes the .pvd collection `path` listing `frames`. \throws gencoord::OutputError
void write_pvd(const std::string& path, const std::vector<PvdFrame>& frames);

/// A run's frames in one folder: <folder>/<name>_000000.vtu, _000001.vtu, ... and
/// <folder>/<name>.pvd, rewritten after every frame so that it lists the frames written so far.
class VtkSeriesWriter {
 public:
  /// Creates `folder` if needed. \throws gencoord::OutputError if it cannot be created.
  explicit VtkSeriesWriter(std::string folder, std::string name = "frames");

  /// Writes the next frame (write_vtu) and the .pvd; returns the frame's path.
  template <int Dim>
  std::string write_frame(const MassSpringSystem<Dim>& s, const SimplexMesh<Dim>* mesh = nullptr);

  const std::vector<PvdFrame>& frames() const { return frames_; }
  std::string pvd_path() const { return folder_ + "/" + name_ + ".pvd"; }

 private:
  std::string folder_, name_;
  std::vector<PvdFrame> frames_;
};

}  // namespace gencoord::deformable
