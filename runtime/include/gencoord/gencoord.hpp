// Umbrella header of the gencoord runtime core.
#pragma once

#include "gencoord/acceleration_jacobians.hpp"
#include "gencoord/csv_writer.hpp"
#include "gencoord/cubic_spline.hpp"
#include "gencoord/dynamics.hpp"
#include "gencoord/errors.hpp"
#include "gencoord/explicit_steps.hpp"
#include "gencoord/implicit_steps.hpp"
#include "gencoord/integrators.hpp"
#include "gencoord/inverse_dynamics.hpp"
#include "gencoord/model_traits.hpp"
#include "gencoord/script.hpp"
#include "gencoord/scripted_dynamics.hpp"
#include "gencoord/scripted_simulate.hpp"
#include "gencoord/scripted_steps.hpp"
#include "gencoord/simulate.hpp"
#include "gencoord/state.hpp"
