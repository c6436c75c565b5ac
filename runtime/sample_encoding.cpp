#include "runtime/sample_encoding.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace boxgen::runtime {

namespace {

struct TypeInfo {
  SampleType type;
  std::string_view name;
};
constexpr TypeInfo kTypes[] = {{SampleType::Int8, "int8"},       {SampleType::UInt8, "uint8"},
                               {SampleType::Int16, "int16"},     {SampleType::UInt16, "uint16"},
                               {SampleType::Int32, "int32"},     {SampleType::UInt32, "uint32"},
                               {SampleType::Float32, "float32"}, {SampleType::Float64, "float64"}};

// Calls f(S{}) with S the C++ type of `type`.
template <class F>
decltype(auto) visit(SampleType type, F&& f) {
  switch (type) {
    case SampleType::Int8:
      return f(std::int8_t{});
    case SampleType::UInt8:
      return f(std::uint8_t{});
    case SampleType::Int16:
      return f(std::int16_t{});
    case SampleType::UInt16:
      return f(std::uint16_t{});
    case SampleType::Int32:
      return f(std::int32_t{});
    case SampleType::UInt32:
      return f(std::uint32_t{});
    case SampleType::Float32:
      return f(float{});
    case SampleType::Float64:
      break;
  }
  return f(double{});
}

}  // namespace

SampleType parse_sample_type(std::string_view text) {
  if (text == "float") return SampleType::Float32;
  if (text == "double") return SampleType::Float64;
  for (const TypeInfo& t : kTypes)
    if (t.name == text) return t.type;
  throw std::invalid_argument(fmt::format(
      "--type must be int8, uint8, int16, uint16, int32, uint32, float32 or float64, got '{}'",
      text.substr(0, 40)));
}

std::string_view sample_type_name(SampleType type) {
  for (const TypeInfo& t : kTypes)
    if (t.type == type) return t.name;
  return "float64";
}

std::size_t sample_type_size(SampleType type) {
  return visit(type, [](auto tag) { return sizeof(tag); });
}

bool is_integer_type(SampleType type) {
  return visit(type, [](auto tag) { return std::is_integral_v<decltype(tag)>; });
}

double sample_type_lowest(SampleType type) {
  return visit(type, [](auto tag) {
    return static_cast<double>(std::numeric_limits<decltype(tag)>::lowest());
  });
}

double sample_type_highest(SampleType type) {
  return visit(type, [](auto tag) {
    return static_cast<double>(std::numeric_limits<decltype(tag)>::max());
  });
}

template <class T>
EncodedSamples encode_samples(std::span<const T> values, SampleType type) {
  EncodedSamples out;
  out.type = type;
  out.bytes.resize(values.size() * sample_type_size(type));
  visit(type, [&](auto tag) {
    using S = decltype(tag);
    constexpr double lo = static_cast<double>(std::numeric_limits<S>::lowest());
    constexpr double hi = static_cast<double>(std::numeric_limits<S>::max());
    std::uint64_t clamped = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
      double x = static_cast<double>(values[i]);
      S s{};
      if constexpr (std::is_integral_v<S>) {
        x = std::nearbyint(x);  // the default rounding mode: to nearest, ties to even
        if (!(x >= lo)) {       // NaN too: the writers refuse non-finite samples before this
          x = lo;
          ++clamped;
        } else if (x > hi) {
          x = hi;
          ++clamped;
        }
        s = static_cast<S>(x);
      } else {
        if (std::isfinite(x) && (x < lo || x > hi)) ++clamped;
        s = static_cast<S>(x < lo   ? -std::numeric_limits<S>::infinity()
                           : x > hi ? std::numeric_limits<S>::infinity()
                                    : x);
      }
      std::memcpy(out.bytes.data() + i * sizeof(S), &s, sizeof(S));
    }
    out.clamped = clamped;
  });
  return out;
}

template EncodedSamples encode_samples<float>(std::span<const float>, SampleType);
template EncodedSamples encode_samples<double>(std::span<const double>, SampleType);

}  // namespace boxgen::runtime
