#include <sealfe/film/film_loads.h>

#include <cmath>

namespace sealfe
{
nlohmann::json FilmLoads::to_json() const
{
  return {{"force_z", force_z},
          {"moment_x", moment_x},
          {"moment_y", moment_y},
          {"moment_restoring", moment_restoring},
          {"moment_transverse", moment_transverse},
          {"leakage_inner", leakage_inner},
          {"leakage_outer", leakage_outer},
          {"friction_torque", friction_torque},
          {"min_film", min_film},
          {"max_pressure", max_pressure},
          {"min_pressure", min_pressure},
          {"cavitated_fraction", cavitated_fraction},
          {"area", area},
          {"squeeze_flow", squeeze_flow},
          {"contact_force", contact_force},
          {"contact_moment_x", contact_moment_x},
          {"contact_moment_y", contact_moment_y},
          {"contact_area_fraction", contact_area_fraction},
          {"min_film_over_sigma", std::isfinite(min_film_over_sigma)
                                      ? nlohmann::json(min_film_over_sigma)
                                      : nlohmann::json(nullptr)}};
}
} // namespace sealfe
