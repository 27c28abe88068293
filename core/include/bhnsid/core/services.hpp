#pragma once
// Services: objects implementing core-declared interfaces, published by one plugin under a
// capability it implements and looked up by others through that name.
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace bhnsid::core {

/// Base of every core-declared interface (Eos, EllipticEquation, ...). Defined out of line in the
/// core library so that its type information is unique across plugins.
class Service {
 public:
  virtual ~Service();
};

class Services {
 public:
  /// Called by the core with the capabilities the publishing plugin implements.
  void publish_raw(const std::string& plugin, const std::string& capability, std::shared_ptr<Service> service);

  template <class T>
  T* find(const std::string& capability) const {
    auto it = entries_.find(capability);
    return it == entries_.end() ? nullptr : dynamic_cast<T*>(it->second.service.get());
  }

  /// The service under `capability`, with a clear error when it is missing or has another interface.
  template <class T>
  T& get(const std::string& capability) const {
    T* service = find<T>(capability);
    if (!service) missing(capability);
    return *service;
  }

  /// Every published service implementing T (e.g. all EllipticEquation services), in publication order.
  template <class T>
  std::vector<T*> all() const {
    std::vector<T*> result;
    for (const auto& name : order_)
      if (auto* s = dynamic_cast<T*>(entries_.at(name).service.get())) result.push_back(s);
    return result;
  }

  std::vector<std::string> capabilities() const { return order_; }

 private:
  [[noreturn]] void missing(const std::string& capability) const;
  struct Entry {
    std::string plugin;
    std::shared_ptr<Service> service;
  };
  std::map<std::string, Entry> entries_;
  std::vector<std::string> order_;
};

}  // namespace bhnsid::core
