#pragma once
// Data files compiled into the binary (see core/embed_data.cmake): the CIE observer and the
// standard illuminants, so presets work without any file next to the executable.
#include <string>

namespace kasha {

// The text of the embedded file with this base name, or nullptr.
const char* embeddedFile(const std::string& name);

}  // namespace kasha
