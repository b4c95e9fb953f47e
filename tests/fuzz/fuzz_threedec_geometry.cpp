// Fuzzes the 3DEC deck reader and writer (io/threedec_geometry.hpp) as `blockdem` reads a .3ddat geometry file: the
// deck's text read into blocks, and the blocks it gave written as a deck and read again, which must give them back
// exactly. A deck is refused with InputError (a block the writer cannot write, with InvalidArgument) or read;
// nothing else may happen.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>

#include "blockdem/core/error.hpp"
#include "blockdem/io/threedec_geometry.hpp"

namespace {

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_threedec_geometry: %s\n", what.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto deck = blockdem::io::read_threedec_deck(text, "fuzz.3ddat");
    for (const auto& b : deck.blocks)
      for (const auto& f : b.faces)
        for (int k : f)
          if (k < 0 || static_cast<std::size_t>(k) >= b.vertices.size()) finding(b.origin + ": a face refers to no vertex");
    std::ostringstream out;
    blockdem::io::write_threedec_deck(out, deck.blocks, "fuzz");
    const auto again = blockdem::io::read_threedec_deck(out.str(), "again.3ddat");
    if (again.blocks.size() != deck.blocks.size()) finding("the written deck reads back to another number of blocks");
    for (std::size_t i = 0; i < deck.blocks.size(); ++i)
      if (again.blocks[i].vertices != deck.blocks[i].vertices || again.blocks[i].faces != deck.blocks[i].faces ||
          again.blocks[i].group != deck.blocks[i].group)
        finding(deck.blocks[i].origin + ": the block written and read again is another block");
  } catch (const blockdem::InvalidArgument&) {
  } catch (const blockdem::InputError&) {
  }
  return 0;
}
