// The sample types a volume file can store, and the one conversion of float or double samples
// into them for writing (nrrd_io.h, nifti_io.h): `--type` of boxrecon's writing commands.
//
// Integer types hold the values rounded to the nearest integer (ties to even, as NumPy's rint);
// values beyond the type's range are clamped to it and counted, so a command can say how many
// (an interpolating filter overshoots near edges: 256 in a uint8 volume). Float32 rounds to
// nearest; a finite double beyond float's range becomes +-infinity as IEEE arithmetic does, and
// is counted as clamped too.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace boxgen::runtime {

enum class SampleType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

// "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32" (also "float"), "float64"
// (also "double"); std::invalid_argument (one line, naming the choices) for anything else.
SampleType parse_sample_type(std::string_view text);
// The name parse_sample_type reads ("float32", "float64" for the floating types).
std::string_view sample_type_name(SampleType type);
std::size_t sample_type_size(SampleType type);
bool is_integer_type(SampleType type);
// The type's smallest and largest values (the floating types: +-their largest finite value).
double sample_type_lowest(SampleType type);
double sample_type_highest(SampleType type);

// Samples converted to `type`, in native byte order.
struct EncodedSamples {
  SampleType type = SampleType::Float32;
  std::vector<std::byte> bytes;
  std::uint64_t clamped = 0;  // values beyond the type's range, set to its nearest end
};

template <class T>
EncodedSamples encode_samples(std::span<const T> values, SampleType type);

extern template EncodedSamples encode_samples<float>(std::span<const float>, SampleType);
extern template EncodedSamples encode_samples<double>(std::span<const double>, SampleType);

}  // namespace boxgen::runtime
