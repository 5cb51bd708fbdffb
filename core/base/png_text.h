// core/base/png_text.h — provenance for a PNG another program drew (gnuplot's plots): the same tEXt
// chunks core/base/image.h writePng gives our own PNGs ("Software", "shadowlab:command",
// "shadowlab:parameters"), added through libpng to a file already on disk.
#pragma once

#include <string>

#include "core/base/provenance.h"

namespace sl {

// Reads the PNG at `path` (any colour type and bit depth, pixels kept byte for byte), adds the
// tEXt chunks of `provenance` (replacing existing ones of the same keywords) and writes it back
// through a temporary that is renamed into place. Throws InputError naming the path.
void addPngProvenance(const std::string& path, const Provenance& provenance);

}  // namespace sl
