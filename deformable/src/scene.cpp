// SPDX-License-Identifier: BSD-3-Clause
// Several objects in one system (scene.hpp).
#include "gencoord/deformable/scene.hpp"

#include <algorithm>

#include "gencoord/deformable/errors.hpp"

namespace gencoord::deformable {

template <int Dim>
int append_object(MassSpringSystem<Dim>& scene, const MassSpringSystem<Dim>& object) {
  if (scene.steps != 0)
    throw ObjectError("append_object: the scene has taken steps; append objects before simulating",
                      -1, -1);
  const int offset = scene.num_nodes();
  const int count = offset + object.num_nodes();
  const bool empty = offset == 0;
  scene.x.conservativeResize(Dim, count);
  scene.x.rightCols(object.num_nodes()) = object.x;
  scene.v.conservativeResize(Dim, count);
  scene.v.rightCols(object.num_nodes()) = object.v;
  scene.mass.conservativeResize(count);
  scene.mass.tail(object.num_nodes()) = object.mass;
  scene.pinned.insert(scene.pinned.end(), object.pinned.begin(), object.pinned.end());
  const int first_spring = static_cast<int>(scene.springs.size());
  for (Spring sp : object.springs) {
    sp.i += offset;
    sp.j += offset;
    scene.springs.push_back(sp);
  }
  for (Hinge hinge : object.hinges) {
    for (int& n : hinge.nodes) n += offset;
    if (hinge.spring >= 0) hinge.spring += first_spring;
    scene.hinges.push_back(hinge);
  }
  for (VolumeTerm<Dim> term : object.volume_terms) {
    for (int& n : term.nodes) n += offset;
    for (int& k : term.springs) k += first_spring;
    scene.volume_terms.push_back(term);
  }
  for (ContinuumElement<Dim> element : object.elements) {
    for (int& n : element.nodes) n += offset;
    for (int& k : element.springs) k += first_spring;
    scene.elements.push_back(element);
  }
  for (QuadraticElement<Dim> element : object.quadratic_elements) {
    for (int& n : element.nodes) n += offset;
    for (int& k : element.springs) k += first_spring;
    scene.quadratic_elements.push_back(element);
  }
  scene.wave_speed = empty ? object.wave_speed : std::max(scene.wave_speed, object.wave_speed);
  if (object.collisions) {
    Collisions<Dim> added = *object.collisions;
    for (auto& simplex : added.surface) {
      for (int& n : simplex) n += offset;
    }
    if (!scene.collisions) {
      scene.collisions = std::move(added);
    } else {
      Collisions<Dim>& c = *scene.collisions;
      c.params.omega = std::min(c.params.omega, added.params.omega);
      // each surface keeps its thickness: both lists written out once they differ
      if (!c.surface_thickness.empty() || !added.surface_thickness.empty() ||
          c.params.thickness != added.params.thickness) {
        c.surface_thickness.resize(c.surface.size(), c.params.thickness);
        added.surface_thickness.resize(added.surface.size(), added.params.thickness);
        c.surface_thickness.insert(c.surface_thickness.end(), added.surface_thickness.begin(),
                                   added.surface_thickness.end());
      }
      c.params.thickness = std::min(c.params.thickness, added.params.thickness);
      // both sidedness lists written out once either object has two-sided simplices
      if (!c.two_sided.empty() || !added.two_sided.empty()) {
        c.two_sided.resize(c.surface.size(), 0);
        added.two_sided.resize(added.surface.size(), 0);
        c.two_sided.insert(c.two_sided.end(), added.two_sided.begin(), added.two_sided.end());
      }
      c.surface.insert(c.surface.end(), added.surface.begin(), added.surface.end());
      c.spheres.insert(c.spheres.end(), added.spheres.begin(), added.spheres.end());
      c.boxes.insert(c.boxes.end(), added.boxes.begin(), added.boxes.end());
    }
  }
  return offset;
}

template int append_object<1>(MassSpringSystem<1>&, const MassSpringSystem<1>&);
template int append_object<2>(MassSpringSystem<2>&, const MassSpringSystem<2>&);
template int append_object<3>(MassSpringSystem<3>&, const MassSpringSystem<3>&);

}  // namespace gencoord::deformable
