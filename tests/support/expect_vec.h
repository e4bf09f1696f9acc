// A glm::vec3 within `tol` of what a test wants, printed both ways when it is not.
#pragma once

#include <gtest/gtest.h>

#include <glm/glm.hpp>

namespace cpgi::test {

inline void expectNear(const glm::vec3& got, const glm::vec3& want, float tol = 1e-5f) {
  EXPECT_LE(glm::length(got - want), tol) << "got (" << got.x << ", " << got.y << ", " << got.z << ") want ("
                                          << want.x << ", " << want.y << ", " << want.z << ")";
}

}  // namespace cpgi::test
