#pragma once
/// \file blade_contact_options.hpp
/// \brief The example's contact options of issue #22: --restitution e (the dampers leave the
/// platform at lift-off and land again, Separation::Separate with Newton's coefficient e) and
/// --ends stop|extend (what a contact point does at a platform end). docs/blade_damper.md.

#include <stickslip/model.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace blade {

/// Contact choices of the scene (defaults: the paper's permanent contact, stop at an end).
struct ContactOptions {
  /// >= 0: every damper separates at lift-off with this coefficient of restitution; < 0: a
  /// lift-off stops the run (default).
  double restitution = -1.0;
  /// Impacts approaching slower than this land (PointDamper::landing_speed) [m/s].
  double landing_speed = 1e-4;
};

/// The option lines of --help.
inline const char* contact_options_help() {
  return "  --restitution e        dampers leave the platform at lift-off and land again with\n"
         "                         Newton's coefficient e in [0, 1] (default: stop at lift-off)\n"
         "  --ends stop|extend     at a platform end: stop the run (default) or continue the end\n"
         "                         elements' shapes (same as --beyond-ends)\n";
}

/// Parses `a` (argv[i]) when it is a contact option, reading its value with `next` (which
/// advances i); returns false for any other option. Throws std::invalid_argument on a bad value.
template <class Next, class ModelOptions>
bool parse_contact_option(const std::string& a, Next&& next, int& i, ContactOptions& contact,
                          ModelOptions& model) {
  if (a == "--restitution") {
    const std::string v = next(i);
    const double e = std::stod(v);
    if (!(e >= 0.0 && e <= 1.0)) throw std::invalid_argument("--restitution expects e in [0, 1], got " + v);
    contact.restitution = e;
    return true;
  }
  if (a == "--ends") {
    const std::string v = next(i);
    if (v == "stop") model.end_policy = stickslip::EndPolicy::Throw;
    else if (v == "extend") model.end_policy = stickslip::EndPolicy::Extrapolate;
    else throw std::invalid_argument("--ends expects stop or extend, got " + v);
    return true;
  }
  return false;
}

/// Applies the contact choices to the scene's dampers.
template <class Damper>
void apply_contact_options(const ContactOptions& contact, std::vector<Damper>& dampers) {
  if (contact.restitution < 0) return;
  for (Damper& d : dampers) {
    d.separation = stickslip::Separation::Separate;
    d.restitution = contact.restitution;
    d.landing_speed = contact.landing_speed;
  }
}

}  // namespace blade
