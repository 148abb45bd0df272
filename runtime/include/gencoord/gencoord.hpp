// Umbrella header of the gencoord runtime core.
#pragma once

#include "gencoord/acceleration_jacobians.hpp"
#include "gencoord/csv_writer.hpp"
#include "gencoord/dynamics.hpp"
#include "gencoord/errors.hpp"
#include "gencoord/explicit_steps.hpp"
#include "gencoord/implicit_steps.hpp"
#include "gencoord/integrators.hpp"
#include "gencoord/model_traits.hpp"
#include "gencoord/simulate.hpp"
#include "gencoord/state.hpp"
