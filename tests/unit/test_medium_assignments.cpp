// The medium-assignment check of scene loading (scene/medium_consistency.h): a camera declared in
// a medium it is not in, and a sphere inside another whose exterior is not the outer one's interior,
// are one-line errors naming the field; the consistent nesting loads.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

// Two concentric spheres of media in front of the camera, over a lit floor.
std::string scene(const std::string& cameraMedium, const std::string& innerExterior) {
  return R"({
    "camera": {"position": [0, 1, -4], "look_at": [0, 1, 0], "fov": 40, "resolution": [8, 8])" + cameraMedium + R"(},
    "materials": {"white": {"type": "lambertian", "reflectance": 0.5}},
    "media": {"fog": {"type": "homogeneous", "sigma_s": 0.5}, "ink": {"type": "homogeneous", "sigma_a": 2}},
    "shapes": [{"type": "rectangle", "center": [0, 0, 0], "u": [0, 0, 3], "v": [3, 0, 0], "material": "white"},
               {"type": "rectangle", "center": [0, 3, 0], "u": [0.5, 0, 0], "v": [0, 0, 0.5], "material": "white",
                "emission": {"radiance": 1, "two_sided": true}},
               {"type": "sphere", "center": [0, 1, 0], "radius": 1, "interior": "fog", "name": "outer"},
               {"type": "sphere", "center": [0, 1, 0], "radius": 0.4, "interior": "ink", "name": "inner")" +
         innerExterior + R"(}]
  })";
}

std::string loadError(const std::string& text) {
  try {
    loadSceneFromString(text, "media.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MediumAssignments, ConsistentNestingLoads) {
  EXPECT_EQ(loadError(scene("", R"(, "exterior": "fog")")), "");
}

TEST(MediumAssignments, ACameraOutsideItsDeclaredMediumIsAnError) {
  EXPECT_CONTAINS(loadError(scene(R"(, "medium": "fog")", R"(, "exterior": "fog")")),
                  "media.json: /camera/medium: a ray from the camera reaches shape 'outer' in medium 'fog'");
}

TEST(MediumAssignments, AnInnerShapeWhoseExteriorIsNotTheOuterInteriorIsAnError) {
  EXPECT_CONTAINS(loadError(scene("", "")),
                  "media.json: /shapes/3: a ray from the camera reaches shape 'inner' in medium 'fog' (after crossing "
                  "shape 'outer'), but its exterior is vacuum");
}

}  // namespace
}  // namespace kasha
