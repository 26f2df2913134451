// BandRoundRule: whether the next round of the JFO active-set polish (JFOSolver::polish) solves
// only a band about the last flips or the whole system, from the flips of the rounds so far.
#pragma once

#include <cstddef>
#include <limits>

namespace sealfe
{
/// A band round solves only for the nodes near the last flips (a small factorisation); a global
/// round solves the whole system and is the only one that can confirm the set. After each round
/// the next is a band round when:
/// - band rounds are still allowed in this polish: no global round has flipped more nodes than
///   the global round before it (band rounds then drove the set astray: measured on an
///   under-resolved 2688-dof wavy mesh);
/// - the round flipped some nodes, but fewer than `max_band_seeds` (more are found faster by a
///   global round);
/// - fewer than max_in_a_row band rounds ran in a row;
/// - after a band round: its flips fell, or stayed as many with none of them a node that flipped
///   in the round before. A cavity boundary that creeps one node per round stays in band rounds
///   (the tilted seal at 1.05e6 dofs: one node 513 dofs further each round for four rounds, where
///   a global round costs a low-rank update of 1.8-2.5 s and a band round ~0.1 s); a set that
///   goes back and forth flips the same nodes again and goes to a global round. (A longer cycle,
///   two sets flipping in turn, runs into the cap.)
class BandRoundRule
{
public:
  /// Band rounds in a row before a global round checks the set.
  static constexpr unsigned int max_in_a_row = 10;

  explicit BandRoundRule(const std::size_t max_band_seeds) : max_band_seeds(max_band_seeds) {}

  /// After a round (`was_band`: a band round, else a global one) that flipped `flips` nodes,
  /// `flips_back` of them also flipped in the round before: whether the next round is a band
  /// round.
  bool next_is_band(const bool was_band, const unsigned int flips, const unsigned int flips_back)
  {
    band_in_a_row = was_band ? band_in_a_row + 1 : 0;
    if (!was_band)
    {
      if (flips > last_global_flips)
        band_allowed = false;
      last_global_flips = flips;
    }
    const bool band =
        band_allowed && flips > 0 && flips < max_band_seeds && band_in_a_row < max_in_a_row &&
        (band_in_a_row == 0 || flips < last_flips || (flips == last_flips && flips_back == 0));
    last_flips = flips;
    return band;
  }

  /// Whether band rounds may still follow in this polish.
  bool allows_band_rounds() const { return band_allowed; }

private:
  std::size_t max_band_seeds;
  unsigned int band_in_a_row = 0;
  // (max: band rounds from the start continue while their flips decrease)
  unsigned int last_flips = std::numeric_limits<unsigned int>::max(),
               last_global_flips = std::numeric_limits<unsigned int>::max();
  bool band_allowed = true;
};
} // namespace sealfe
