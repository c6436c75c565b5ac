// Which prefilter turns a volume's samples into the coefficients a filter's spline is evaluated
// on, with its parameter where it takes one. Parsed from the text every command and the Python
// module accept (parse_prefilter), printed back by text():
//
//   none          the samples themselves
//   q1, q2        the generator's quasi-interpolation prefilters Q^I, Q^II (FIR taps)
//   q1opt, q2opt  the same shells, free parameters minimising the mean error kernel (FIR taps)
//   qfir:K        the FIR interpolation prefilter on the lattice shells 0..K (fir_interpolation.h)
//   interp        interpolation: the spline passes through every sample (runtime/interpolation.h;
//                 regularised where the filter's symbol vanishes)
//   interp:L      the same with the Tikhonov weight L (relative to max |A|^2) given; 0 asks for
//                 exact interpolation
#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace boxgen::runtime {

class PrefilterChoice {
 public:
  enum class Kind { None, Q1, Q2, Q1Opt, Q2Opt, QFir, Interp };

  // The choices without a parameter, as values: PrefilterChoice::Q1.
  static const PrefilterChoice None, Q1, Q2, Q1Opt, Q2Opt;

  constexpr PrefilterChoice() = default;
  constexpr explicit PrefilterChoice(Kind kind, std::optional<double> parameter = std::nullopt)
      : kind_(kind), parameter_(parameter) {}
  // Interpolation; lambda: the Tikhonov weight relative to max |A|^2, or the filter's default.
  static constexpr PrefilterChoice interp(std::optional<double> lambda = std::nullopt) {
    return PrefilterChoice(Kind::Interp, lambda);
  }

  // qfir:K, the FIR interpolation prefilter on the shells 0..K.
  static constexpr PrefilterChoice qfir(int last_shell) {
    return PrefilterChoice(Kind::QFir, last_shell);
  }

  constexpr Kind kind() const noexcept { return kind_; }
  // qfir:K: K.
  constexpr int fir_shells() const noexcept { return static_cast<int>(parameter_.value_or(0)); }
  // The parameter given after the colon, if any (interp: lambda; qfir: K).
  constexpr std::optional<double> parameter() const noexcept { return parameter_; }
  // Is it a table of FIR taps (SplineFilter::prefilter gives them)? none counts: one tap.
  constexpr bool is_fir() const noexcept { return kind_ != Kind::Interp; }
  // The text parse_prefilter reads back: "none", "q1", "interp", "interp:0.001".
  std::string text() const;

  friend constexpr bool operator==(const PrefilterChoice& a, const PrefilterChoice& b) noexcept {
    return a.kind_ == b.kind_ && a.parameter_ == b.parameter_;
  }

 private:
  Kind kind_ = Kind::None;
  std::optional<double> parameter_;
};

inline constexpr PrefilterChoice PrefilterChoice::None{PrefilterChoice::Kind::None};
inline constexpr PrefilterChoice PrefilterChoice::Q1{PrefilterChoice::Kind::Q1};
inline constexpr PrefilterChoice PrefilterChoice::Q2{PrefilterChoice::Kind::Q2};
inline constexpr PrefilterChoice PrefilterChoice::Q1Opt{PrefilterChoice::Kind::Q1Opt};
inline constexpr PrefilterChoice PrefilterChoice::Q2Opt{PrefilterChoice::Kind::Q2Opt};

// "none" | "q1" | "q2" | "q1opt" | "q2opt" | "qfir:K" (K = 0..8) | "interp" | "interp:L" (L finite,
// >= 0 and at most 1); anything else: std::invalid_argument, one line.
PrefilterChoice parse_prefilter(std::string_view text);

// "none | q1 | q2 | q1opt | q2opt | qfir:K | interp[:L]": the choices, for help texts.
inline constexpr const char* kPrefilterChoices =
    "none | q1 | q2 | q1opt | q2opt | qfir:K | interp[:LAMBDA]";

}  // namespace boxgen::runtime
