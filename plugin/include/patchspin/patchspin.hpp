// Umbrella header of patchspin::core.
#pragma once

#include <patchspin/friction_block.hpp>
#include <patchspin/geometry.hpp>
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>
#include <patchspin/types.hpp>
