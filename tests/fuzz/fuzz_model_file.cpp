// Fuzzes the model file reader (analysis/model_file.hpp) as `blockdem run` and `blockdem check` use it: the file's
// text read into a structure and a study, both checked, and the contacts of the blocks it built detected. A file
// is refused with InvalidArgument (or InputError) or read; nothing else may happen.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/model/contact_detection.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto file = blockdem::analysis::parse_model_file(text, "models/fuzz.json", "models");
    file.structure.validate();
    file.study.validate();
    if (file.structure.model.bodies.size() <= 200) {  // detection is quadratic at worst: a bounded number of blocks
      auto settings = file.structure.contacts;
      settings.kinds = file.study.contacts;
      file.structure.laws.fill(settings);
      (void)blockdem::model::detect_contacts(file.structure.model.bodies, settings);
    }
  } catch (const blockdem::InvalidArgument&) {
  } catch (const blockdem::InputError&) {
  }
  return 0;
}
