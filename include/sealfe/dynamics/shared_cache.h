// SharedCache: results of an expensive evaluation kept by key (a coefficient table by file name,
// film coefficients by pair of ring speeds), shared by all copies of the cache's owner.
#pragma once

#include <map>
#include <memory>

namespace sealfe
{
/// A map from keys to values computed once. Copies share the entries (a parameter study copies
/// its input and keeps what was computed). Not thread-safe, as the film models it serves.
template <typename Key, typename Value>
class SharedCache
{
public:
  /// The value for `key`, computed by make() on the first request (an exception from make()
  /// leaves nothing behind).
  template <typename Make>
  const Value &get(const Key &key, Make &&make) const
  {
    const auto hit = entries->find(key);
    if (hit != entries->end())
      return hit->second;
    return entries->emplace(key, make()).first->second;
  }
  std::size_t size() const { return entries->size(); }

private:
  std::shared_ptr<std::map<Key, Value>> entries = std::make_shared<std::map<Key, Value>>();
};

} // namespace sealfe
