// The white-furnace check shared by the global and the cell solver tests: every valid texel's green
// radiosity near B = E / (1 − ρ), and the area-weighted mean nearer still.
#pragma once

#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "radiosity/lightmap/atlas.h"

namespace cpgi::testing {

inline void expectFurnace(const LightmapAtlas& atlas, const std::vector<glm::vec3>& radiosity, double expect,
                          double texelTolerance, double meanTolerance) {
  double sum = 0.0, area = 0.0;
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    if (atlas.patch[t] < 0) continue;
    sum += radiosity[t].g * atlas.area[t];
    area += atlas.area[t];
    EXPECT_NEAR(radiosity[t].g, expect, texelTolerance * expect) << "texel " << t;
  }
  EXPECT_NEAR(sum / area, expect, meanTolerance * expect);
}

}  // namespace cpgi::testing
