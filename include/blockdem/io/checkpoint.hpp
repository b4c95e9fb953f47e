#pragma once
// Checkpoints: the complete state of a simulation in a binary file, for a continuation that is bitwise that of the
// uninterrupted run. A small writer/reader pair of raw values and sized vectors, and the file around them: magic
// bytes, format version, the caller's model hash and description, the payload, and an FNV-1a checksum of it.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>
#include <source_location>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "blockdem/core/error.hpp"
#include "blockdem/io/atomic_file.hpp"

namespace blockdem::io {

// ---- hashing ----

/// FNV-1a, 64 bits: the payload checksum, and a helper to build the model hash from what defines a model (its
/// options, file names, sizes). Not cryptographic: it catches corruption and mix-ups, not tampering.
class Hasher {
 public:
  static constexpr std::uint64_t offset_basis = 14695981039346656037ull;
  static constexpr std::uint64_t prime = 1099511628211ull;

  constexpr Hasher() = default;
  constexpr explicit Hasher(std::uint64_t seed) : state_(seed) {}

  Hasher& add_bytes(const void* data, std::size_t size) noexcept {
    const auto* p = static_cast<const unsigned char*>(data);
    std::uint64_t h = state_;
    for (std::size_t i = 0; i < size; ++i) h = (h ^ p[i]) * prime;
    state_ = h;
    return *this;
  }
  /// A number or another trivially copyable value without padding (doubles: their bits, so 0.0 and -0.0 differ).
  template <class T>
    requires(!std::is_pointer_v<T> && !std::is_array_v<T> &&
             ((std::is_trivially_copyable_v<T> && std::has_unique_object_representations_v<T>) || std::is_floating_point_v<T>))
  Hasher& add(const T& value) noexcept {
    return add_bytes(&value, sizeof value);
  }
  /// A string with its length (so that "ab" + "c" and "a" + "bc" differ).
  Hasher& add(std::string_view s) noexcept {
    add(static_cast<std::uint64_t>(s.size()));
    return add_bytes(s.data(), s.size());
  }
  Hasher& add(const char* s) noexcept { return add(std::string_view(s)); }
  Hasher& add(const std::string& s) noexcept { return add(std::string_view(s)); }
  template <class T>
  Hasher& add(const std::vector<T>& v) noexcept {
    add(static_cast<std::uint64_t>(v.size()));
    for (const auto& x : v) add(x);
    return *this;
  }

  constexpr std::uint64_t value() const noexcept { return state_; }

 private:
  std::uint64_t state_ = offset_basis;
};

/// FNV-1a 64 of `size` bytes, continuing from `seed`.
inline std::uint64_t hash_bytes(const void* data, std::size_t size, std::uint64_t seed = Hasher::offset_basis) noexcept {
  return Hasher(seed).add_bytes(data, size).value();
}
inline std::uint64_t hash_bytes(std::string_view s, std::uint64_t seed = Hasher::offset_basis) noexcept {
  return hash_bytes(s.data(), s.size(), seed);
}

// ---- what is written as raw bytes ----

namespace detail {
/// Values written as their bytes: trivially copyable types (not pointers), fixed-size Eigen matrices and
/// quaternions of numbers (their coefficients, contiguous and unpadded: the integrator reads them in place too),
/// and std::arrays of those.
template <class T>
struct Plain : std::bool_constant<std::is_trivially_copyable_v<T> && !std::is_pointer_v<T> && !std::is_member_pointer_v<T>> {};
template <class S, int R, int C, int O, int MR, int MC>
struct Plain<Eigen::Matrix<S, R, C, O, MR, MC>> : std::bool_constant<(R > 0 && C > 0 && std::is_arithmetic_v<S>)> {
  static_assert(!(R > 0 && C > 0) || sizeof(Eigen::Matrix<S, R, C, O, MR, MC>) == sizeof(S) * R * C,
                "a fixed-size Eigen matrix is its coefficients");
};
template <class S, int O>
struct Plain<Eigen::Quaternion<S, O>> : std::is_arithmetic<S> {
  static_assert(sizeof(Eigen::Quaternion<S, O>) == 4 * sizeof(S), "a quaternion is its four coefficients");
};
template <class T, std::size_t N>
struct Plain<std::array<T, N>> : Plain<T> {};

template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {};
template <class T>
struct IsArray : std::false_type {};
template <class T, std::size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};

/// Whether a stored value of type T can be bytes that are no value of T, which the reader then checks: a bool (0 or 1:
/// another byte is undefined behaviour wherever the bool is read), an enumeration that says which values it has (a
/// function valid_enumerator(T), found by argument-dependent lookup: a value out of range would be a silent wrong
/// branch), std::arrays of those, and plain classes that list their bool members (a static member function
/// checkpoint_flags() returning an array of member pointers).
template <class T>
constexpr bool has_invalid_bytes() {
  if constexpr (std::is_same_v<T, bool>) return true;
  else if constexpr (std::is_enum_v<T>) return requires(T e) { valid_enumerator(e); };
  else if constexpr (IsArray<T>::value) return has_invalid_bytes<typename T::value_type>();
  else return requires { T::checkpoint_flags(); };
}

/// The fewest payload bytes one element of type T takes (for the bound on a stored count).
template <class T>
constexpr std::uint64_t min_bytes() {
  if constexpr (Plain<T>::value) return sizeof(T) > 0 ? sizeof(T) : 1;
  else if constexpr (IsVector<T>::value || std::is_same_v<T, std::string>) return sizeof(std::uint64_t);
  else return 1;
}
}  // namespace detail

template <class T>
inline constexpr bool plain_checkpoint_value = detail::Plain<T>::value;

/// The compiler's spelling of type T (from the name of a function of T: no RTTI needed), to check that a checkpoint
/// is read by the type that wrote it.
template <class T>
std::string type_name() {
#if defined(__cpp_lib_source_location)
  std::string_view name = std::source_location::current().function_name();
#else  // Clang before 15 with libstdc++ has no std::source_location; the same text, from the compiler
  std::string_view name = __PRETTY_FUNCTION__;
#endif
  // GCC and Clang: "... type_name() [with T = X; ...]" or "[T = X]": X alone; other compilers: the whole name.
  if (const auto begin = name.find("T = "); begin != std::string_view::npos) {
    name.remove_prefix(begin + 4);
    name = name.substr(0, name.find_first_of(";]"));
  }
  return std::string(name);
}

// ---- writer and reader ----

/// Writes values to a stream and hashes what it writes. write(): trivially copyable values (and fixed-size Eigen
/// objects) as their bytes, in this machine's byte order; std::vector and std::string as a uint64 count followed by
/// the elements; std::arrays of other types element by element; objects with save_state(CheckpointWriter&) through
/// it. The visit form used by the state classes: w("what", value), w.same_size("what", vector),
/// w.check("what", value) (the reader checks the value against its own): the writer ignores the names.
class CheckpointWriter {
 public:
  static constexpr bool loading = false;

  explicit CheckpointWriter(std::ostream& out, std::string file = "(stream)") : out_(&out), file_(std::move(file)) {}

  void write_bytes(const void* data, std::size_t size) {
    if (size == 0) return;
    out_->write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!*out_) throw InvalidArgument("checkpoint '" + file_ + "': cannot write (disk full or stream closed?)");
    hasher_.add_bytes(data, size);
    bytes_ += size;
  }

  template <class T>
  void write(const T& value) {
    if constexpr (detail::Plain<T>::value) {
      write_bytes(&value, sizeof value);
    } else if constexpr (detail::IsVector<T>::value) {
      write(static_cast<std::uint64_t>(value.size()));
      using E = typename T::value_type;
      if constexpr (detail::Plain<E>::value)
        write_bytes(value.data(), value.size() * sizeof(E));
      else
        for (const auto& e : value) write(e);
    } else if constexpr (std::is_same_v<T, std::string>) {
      write(static_cast<std::uint64_t>(value.size()));
      write_bytes(value.data(), value.size());
    } else if constexpr (detail::IsArray<T>::value) {
      for (const auto& e : value) write(e);
    } else if constexpr (requires(CheckpointWriter& w) { value.save_state(w); }) {
      value.save_state(*this);
    } else {
      static_assert(sizeof(T) == 0, "CheckpointWriter: no way to write this type");
    }
  }

  template <class T>
  void operator()(const char* /*what*/, const T& value) { write(value); }
  template <class T>
  void same_size(const char* /*what*/, const std::vector<T>& value) { write(value); }
  template <class T>
  void check(const char* /*what*/, const T& value) { write(value); }

  std::uint64_t checksum() const noexcept { return hasher_.value(); }
  std::uint64_t bytes() const noexcept { return bytes_; }
  const std::string& file() const noexcept { return file_; }

 private:
  std::ostream* out_;
  std::string file_;
  Hasher hasher_;
  std::uint64_t bytes_ = 0;
};

/// The reverse of CheckpointWriter, from at most `size` bytes of a stream. Every count is checked against the bytes
/// left before anything is allocated; a short read, a count beyond what is left, a vector whose stored size differs
/// from the one it must keep (same_size) or a value that differs from the expected one (check) throws
/// InvalidArgument naming the file and what was being read.
class CheckpointReader {
 public:
  static constexpr bool loading = true;
  static constexpr std::uint64_t unbounded = std::numeric_limits<std::uint64_t>::max();

  explicit CheckpointReader(std::istream& in, std::string file = "(stream)", std::uint64_t size = unbounded)
      : in_(&in), file_(std::move(file)), remaining_(size) {}

  [[noreturn]] void fail(std::string_view what, const std::string& problem) const {
    throw InvalidArgument("checkpoint '" + file_ + "': " + problem + " (reading " + std::string(what) + ")");
  }

  void read_bytes(void* data, std::size_t size, std::string_view what) {
    if (size == 0) return;
    if (size > remaining_)
      fail(what, "truncated: " + std::to_string(size) + " bytes needed, " + std::to_string(remaining_) + " left");
    in_->read(static_cast<char*>(data), static_cast<std::streamsize>(size));
    if (in_->gcount() != static_cast<std::streamsize>(size))
      fail(what, "truncated: " + std::to_string(size) + " bytes needed, " + std::to_string(in_->gcount()) + " read");
    if (remaining_ != unbounded) remaining_ -= size;
  }

  template <class T>
  void read(T& value, std::string_view what = "a value") {
    if constexpr (detail::Plain<T>::value) {
      read_bytes(&value, sizeof value, what);
      if constexpr (detail::has_invalid_bytes<T>()) check_stored(value, what);
    } else if constexpr (detail::IsVector<T>::value) {
      using E = typename T::value_type;
      const std::uint64_t n = read_count<E>(what);
      value.resize(static_cast<std::size_t>(n));
      read_elements(value, what);
    } else if constexpr (std::is_same_v<T, std::string>) {
      const std::uint64_t n = read_count<char>(what);
      value.resize(static_cast<std::size_t>(n));
      read_bytes(value.data(), value.size(), what);
    } else if constexpr (detail::IsArray<T>::value) {
      for (auto& e : value) read(e, what);
    } else if constexpr (requires(CheckpointReader& r) { value.load_state(r); }) {
      value.load_state(*this);
    } else {
      static_assert(sizeof(T) == 0, "CheckpointReader: no way to read this type");
    }
  }
  template <class T>
  T read_value(std::string_view what = "a value") {
    T value{};
    read(value, what);
    return value;
  }

  template <class T>
  void operator()(const char* what, T& value) { read(value, what); }
  /// A vector whose size this object already has (the model's blocks, nodes): the stored count must be it.
  template <class T>
  void same_size(const char* what, std::vector<T>& value) {
    const std::uint64_t n = read_count<T>(what);
    if (n != value.size())
      fail(what, "another model: " + std::to_string(n) + " stored, this model has " + std::to_string(value.size()));
    read_elements(value, what);
  }
  /// A value that must equal this object's own (a layout or a size).
  template <class T>
  void check(const char* what, const T& expected) {
    T stored{};
    read(stored, what);
    if (!(stored == expected)) {
      if constexpr (std::is_arithmetic_v<T>)
        fail(what, "stored " + std::to_string(stored) + ", this simulation has " + std::to_string(expected));
      else if constexpr (std::is_same_v<T, std::string>)
        fail(what, "stored '" + stored + "', this simulation has '" + expected + "'");
      else
        fail(what, "the stored value differs from this simulation's");
    }
  }

  /// Bytes not yet read (unbounded for a reader without a size).
  std::uint64_t remaining() const noexcept { return remaining_; }
  const std::string& file() const noexcept { return file_; }

 private:
  template <class E>
  std::uint64_t read_count(std::string_view what) {
    std::uint64_t n = 0;
    read_bytes(&n, sizeof n, what);
    // No count that the rest of the payload cannot hold (a corrupted count must not allocate terabytes); a reader
    // without a size still refuses more than 2^40 bytes.
    const std::uint64_t limit = remaining_ == unbounded ? (std::uint64_t{1} << 40) : remaining_;
    if (n > limit / detail::min_bytes<E>())
      fail(what, "a count of " + std::to_string(n) + " elements, more than the " + std::to_string(limit) +
                     " bytes left can hold");
    return n;
  }
  template <class V>
  void read_elements(V& value, std::string_view what) {
    using E = typename V::value_type;
    if constexpr (detail::Plain<E>::value) {
      read_bytes(value.data(), value.size() * sizeof(E), what);
      if constexpr (detail::has_invalid_bytes<E>())
        for (const auto& e : value) check_stored(e, what);
    } else
      for (auto& e : value) read(e, what);
  }

  /// A value just read as bytes that not every byte pattern is (detail::has_invalid_bytes): its bools must be 0 or 1
  /// (looked at as bytes, not read as bools), its enumerators valid.
  template <class T>
  void check_stored(const T& value, std::string_view what) const {
    if constexpr (std::is_same_v<T, bool>) {
      static_assert(sizeof(bool) == 1);
      unsigned char byte = 0;
      std::memcpy(&byte, &value, 1);
      if (byte > 1) fail(what, "a flag stored as " + std::to_string(byte) + ", not 0 or 1");
    } else if constexpr (std::is_enum_v<T>) {
      if (!valid_enumerator(value))
        fail(what, "an enumerator out of range (stored " +
                       std::to_string(static_cast<long long>(static_cast<std::underlying_type_t<T>>(value))) + ")");
    } else if constexpr (detail::IsArray<T>::value) {
      for (const auto& e : value) check_stored(e, what);
    } else {
      for (auto member : T::checkpoint_flags()) check_stored(value.*member, what);
    }
  }

  std::istream* in_;
  std::string file_;
  std::uint64_t remaining_;
};

// ---- the file ----

/// The file format: "BLOCKDEM-CKPT" (13 bytes), format version (uint32), model hash (uint64), description (uint64
/// length, bytes), payload size (uint64), payload, FNV-1a 64 of the payload (uint64); numbers in this machine's byte
/// order (a checkpoint is for continuing on the same kind of machine, not an archive format).
inline constexpr std::string_view checkpoint_magic = "BLOCKDEM-CKPT";
/// Raised whenever what a checkpoint holds changes (2: the energy that re-detection added, EnergyReport::contact_update;
/// 3: the timestep hold, TimestepHold; 4: the laws' histories keep the closure impulse, contact/closure_impulse.hpp;
/// 5: the elastic law's history keeps whether a point was ever bonded, and the simulation the timestep of its last
/// move; 6: one gather list of node contact forces for all groups; 7: the work on the element branches summed per
/// tile of 32 elements, DeformableState::element_viscous), so that a checkpoint of an earlier build is refused by
/// name instead of being read out of step.
inline constexpr std::uint32_t checkpoint_format_version = 7;

/// What a checkpoint's header says.
struct CheckpointHeader {
  std::uint32_t version = 0;
  std::uint64_t model_hash = 0;
  std::string description;
  std::uint64_t payload_size = 0;       // bytes
  std::uint64_t payload_offset = 0;     // bytes from the start of the file
};

namespace detail {
inline std::string checkpoint_prefix(const std::string& path) { return "checkpoint '" + path + "': "; }

/// Reads and checks the header (magic, version, the sizes against the file's); leaves `in` at the payload.
inline CheckpointHeader read_checkpoint_header(std::istream& in, const std::string& path, std::uint64_t file_size) {
  const std::string prefix = checkpoint_prefix(path);
  std::array<char, checkpoint_magic.size()> magic{};
  in.read(magic.data(), static_cast<std::streamsize>(magic.size()));
  if (in.gcount() != static_cast<std::streamsize>(magic.size()) ||
      std::string_view(magic.data(), magic.size()) != checkpoint_magic)
    throw InvalidArgument(prefix + "not a blockdem checkpoint (bad magic bytes; expected \"" +
                          std::string(checkpoint_magic) + "\")");
  CheckpointReader header(in, path, file_size - magic.size());
  CheckpointHeader h;
  header.read(h.version, "the format version");
  if (h.version != checkpoint_format_version)
    throw InvalidArgument(prefix + "written by format version " + std::to_string(h.version) + ", this build reads " +
                          std::to_string(checkpoint_format_version));
  header.read(h.model_hash, "the model hash");
  const auto description_size = header.read_value<std::uint64_t>("the description's length");
  if (description_size > (std::uint64_t{1} << 20) || description_size > header.remaining())
    throw InvalidArgument(prefix + "truncated or corrupted header: a description of " + std::to_string(description_size) +
                          " bytes, " + std::to_string(header.remaining()) + " left in the file");
  h.description.resize(static_cast<std::size_t>(description_size));
  header.read_bytes(h.description.data(), h.description.size(), "the description");
  header.read(h.payload_size, "the payload size");
  h.payload_offset = file_size - header.remaining();
  const std::uint64_t expected = h.payload_size + sizeof(std::uint64_t);  // payload and checksum
  if (h.payload_size > header.remaining() || header.remaining() < expected)  // the first: `expected` may wrap
    throw InvalidArgument(prefix + "truncated: the header announces " + std::to_string(h.payload_size) +
                          " bytes of payload and an 8-byte checksum, the file has " + std::to_string(header.remaining()) +
                          " bytes after the header");
  if (header.remaining() > expected)
    throw InvalidArgument(prefix + "corrupted: " + std::to_string(header.remaining() - expected) +
                          " unexpected bytes after the checksum");
  return h;
}
}  // namespace detail

/// The header of the checkpoint at `path` (magic, version and sizes checked; not the payload's checksum).
inline CheckpointHeader read_checkpoint_header(const std::string& path) {
  std::error_code error;
  const auto file_size = std::filesystem::file_size(path, error);
  if (error) throw InvalidArgument(detail::checkpoint_prefix(path) + "cannot read: " + error.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(detail::checkpoint_prefix(path) + "cannot open");
  return detail::read_checkpoint_header(in, path, file_size);
}

/// Writes a checkpoint: the header, then write_payload(CheckpointWriter&), then the checksum; to path + ".part",
/// renamed to `path` when complete (a run stopped while writing leaves the previous checkpoint). model_hash is the
/// caller's hash of what defines the model and the run (io::Hasher); load_checkpoint refuses another one. Throws
/// InvalidArgument naming the file if it cannot be written.
template <class Payload>
void save_checkpoint(const std::string& path, std::uint64_t model_hash, const std::string& description,
                     Payload&& write_payload) {
  write_atomically(path, [&](const std::string& part) {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    if (!out) throw InvalidArgument(detail::checkpoint_prefix(path) + "cannot open '" + part + "' for writing");
    CheckpointWriter header(out, path);
    header.write_bytes(checkpoint_magic.data(), checkpoint_magic.size());
    header.write(checkpoint_format_version);
    header.write(model_hash);
    header.write(description);
    const auto size_at = out.tellp();
    header.write(std::uint64_t{0});  // the payload size, once known
    CheckpointWriter payload(out, path);
    write_payload(payload);
    payload.write(payload.checksum());  // the hash of what came before it
    out.seekp(size_at);
    const std::uint64_t payload_size = payload.bytes() - sizeof(std::uint64_t);
    out.write(reinterpret_cast<const char*>(&payload_size), sizeof payload_size);
    out.close();
    if (!out) throw InvalidArgument(detail::checkpoint_prefix(path) + "cannot write '" + part + "'");
  });
}

/// Reads the checkpoint at `path` with read_payload(CheckpointReader&), after checking, in this order: that the
/// file exists, its magic bytes, its format version, its size against the header's (truncated), the model hash
/// (another model or other options) and the payload's checksum (corrupted); then that read_payload read the whole
/// payload. Each refusal is an InvalidArgument naming the file and what is wrong.
template <class ReadPayload>
void load_checkpoint(const std::string& path, std::uint64_t model_hash, ReadPayload&& read_payload) {
  const std::string prefix = detail::checkpoint_prefix(path);
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw InvalidArgument(prefix + "no such file");
  const auto file_size = std::filesystem::file_size(path, error);
  if (error) throw InvalidArgument(prefix + "cannot read: " + error.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(prefix + "cannot open");
  const CheckpointHeader h = detail::read_checkpoint_header(in, path, file_size);
  if (h.model_hash != model_hash) {
    char hashes[80];
    std::snprintf(hashes, sizeof hashes, "model hash %016llx, this run has %016llx",
                  static_cast<unsigned long long>(h.model_hash), static_cast<unsigned long long>(model_hash));
    throw InvalidArgument(prefix + "the checkpoint is of another model or other options (it holds '" + h.description +
                          "', " + hashes + "); a build for another instruction set (BLOCKDEM_NATIVE, or another "
                          "processor) computes the model differently by rounding, and so another model hash");
  }
  // The checksum first, in chunks, so that a corrupted payload is reported as such and not as whatever the reader
  // would trip over; then the payload again, read.
  {
    CheckpointReader chunks(in, path, h.payload_size + sizeof(std::uint64_t));
    Hasher hasher;
    std::vector<char> buffer(std::size_t{1} << 20);
    for (std::uint64_t left = h.payload_size; left > 0;) {
      const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(left, buffer.size()));
      chunks.read_bytes(buffer.data(), n, "the payload");
      hasher.add_bytes(buffer.data(), n);
      left -= n;
    }
    const auto stored = chunks.read_value<std::uint64_t>("the checksum");
    if (stored != hasher.value()) {
      char sums[80];
      std::snprintf(sums, sizeof sums, "stored %016llx, computed %016llx", static_cast<unsigned long long>(stored),
                    static_cast<unsigned long long>(hasher.value()));
      throw InvalidArgument(prefix + "corrupted payload (checksum mismatch: " + sums + ")");
    }
  }
  in.clear();
  in.seekg(static_cast<std::streamoff>(h.payload_offset));
  CheckpointReader payload(in, path, h.payload_size);
  read_payload(payload);
  if (payload.remaining() != 0)
    throw InvalidArgument(prefix + std::to_string(payload.remaining()) + " bytes of the payload were left unread (the " +
                          "checkpoint holds more state than this simulation reads)");
}

}  // namespace blockdem::io
