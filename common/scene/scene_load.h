#pragma once

#include <filesystem>
#include <string_view>

#include "common/base/file_source.h"
#include "common/scene/load_limits.h"
#include "common/scene/scene_budget.h"
#include "common/scene/scene.h"

namespace glint {

// Loads a scene (the Glint scene format, version 1; docs/scene-format.md)
// from its JSON text, reading the files it names through `files`. Any error
// throws InputError naming the JSON path ("objects[3].radius: must be > 0");
// nothing of a half-read scene escapes.
Scene loadScene(std::string_view text, FileSource& files, const LoadLimits& limits = {});
// The same, counting what the scene will hold against `budget` (which keeps
// the count, so that a caller can hold it through the BVH build).
Scene loadScene(std::string_view text, FileSource& files, SceneBudget& budget);

// The same for a scene file on disk: its files are read relative to its
// folder. Errors start with the file's path.
Scene loadSceneFile(const std::filesystem::path& path, const LoadLimits& limits = {});

}  // namespace glint
