// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// SVG pictures of the demo: chosen frames side by side, and an optional animation.

#include <string>
#include <vector>

#include "frame_output.hpp"
#include "scenarios.hpp"

namespace gencoord::deformable::demo {

/// Draws the frames with the given indices side by side (springs as lines, pinned nodes as
/// squares, the ground if any) into `path`. Throws std::runtime_error on a write error.
void write_svg_panels(const std::string& path, const Scenario& sc,
                      const MassSpringSystem<2>& final_state, const std::vector<Frame>& frames,
                      const std::vector<int>& chosen);

/// Animated SVG (SMIL, plays in a browser) of all frames, looping, in real time.
void write_svg_animation(const std::string& path, const Scenario& sc,
                         const MassSpringSystem<2>& final_state, const std::vector<Frame>& frames);

}  // namespace gencoord::deformable::demo
