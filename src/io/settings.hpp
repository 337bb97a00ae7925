// The scene's keys turned into the typed structs the layers below io work with.
#pragma once

#include "model/parameters.hpp"

namespace bkq {

class Scene;

ModelParams model_from_scene(const Scene& scene);

}  // namespace bkq
