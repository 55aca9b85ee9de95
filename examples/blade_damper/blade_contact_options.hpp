#pragma once
/// \file blade_contact_options.hpp
/// \brief The example's contact options: --restitution e (the dampers leave the
/// platform at lift-off and land again, Separation::Separate with Newton's coefficient e) and
/// --ends stop|extend|wall (what a contact point does at a platform end; a wall reflects it with
/// --wall-restitution). docs/blade_damper.md.

#include <stickslip/model.hpp>

#include <cstdlib>
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
  /// --ends wall: both platform ends are rigid walls (MemberEnd::Wall) with this restitution.
  bool walls = false;
  double wall_restitution = 1.0;
};

/// The demo's contact choices (--demo, unless a contact option is given): the dampers separate
/// at lift-off and land again (e = 0.5), and both platform ends are walls (e = 0.5) at which a
/// damper comes to rest, in contact or in flight (docs/model_separation.md "Resting at a wall", "Held at a
/// wall in flight"), so that every preload of the demo's sweep runs to its end.
inline ContactOptions demo_contact_options() {
  ContactOptions c;
  c.restitution = 0.5;
  c.walls = true;
  c.wall_restitution = 0.5;
  return c;
}

/// The option lines of --help.
inline const char* contact_options_help() {
  return "  --restitution e        dampers leave the platform at lift-off and land again with\n"
         "                         Newton's coefficient e in [0, 1] (default: stop at lift-off)\n"
         "  --ends stop|extend|wall  at a platform end: stop the run (default), continue the end\n"
         "                         elements' shapes (same as --beyond-ends), or reflect the\n"
         "                         contact point from a rigid wall (V -> -e V; a damper pushed\n"
         "                         into it comes to rest against it)\n"
         "  --wall-restitution e   the walls' coefficient of restitution (default 1)\n";
}

/// Parses `a` (argv[i]) when it is a contact option, reading its value with `next` (which
/// advances i); returns false for any other option. Throws std::invalid_argument on a bad value.
template <class Next, class ModelOptions>
bool parse_contact_option(const std::string& a, Next&& next, int& i, ContactOptions& contact,
                          ModelOptions& model) {
  // A coefficient of restitution in [0, 1], read as the value of option `a`.
  auto restitution = [&] {
    const std::string v = next(i);
    char* end = nullptr;
    const double e = std::strtod(v.c_str(), &end);
    if (v.empty() || end != v.c_str() + v.size() || !(e >= 0.0 && e <= 1.0))
      throw std::invalid_argument(a + " expects e in [0, 1], got '" + v + "'");
    return e;
  };
  if (a == "--restitution") {
    contact.restitution = restitution();
    return true;
  }
  if (a == "--ends") {
    const std::string v = next(i);
    contact.walls = v == "wall";
    if (v == "stop" || v == "wall") model.end_policy = stickslip::EndPolicy::Throw;
    else if (v == "extend") model.end_policy = stickslip::EndPolicy::Extrapolate;
    else throw std::invalid_argument("--ends expects stop, extend or wall, got " + v);
    return true;
  }
  if (a == "--wall-restitution") {
    contact.wall_restitution = restitution();
    return true;
  }
  return false;
}

/// Applies the contact choices to the scene's dampers.
template <class Damper>
void apply_contact_options(const ContactOptions& contact, std::vector<Damper>& dampers) {
  for (Damper& d : dampers) {
    if (contact.walls) {
      d.start_end = d.finish_end = stickslip::MemberEnd::Wall;
      d.wall_restitution = contact.wall_restitution;
    }
    if (contact.restitution < 0) continue;
    d.separation = stickslip::Separation::Separate;
    d.restitution = contact.restitution;
    d.landing_speed = contact.landing_speed;
  }
}

}  // namespace blade
