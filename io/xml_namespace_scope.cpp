#include "io/xml_namespace_scope.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace conicloc::io {
namespace {

constexpr std::string_view kXmlnsPrefix = "xmlns:";
constexpr std::string_view kXmlNamespace = "http://www.w3.org/XML/1998/namespace";

std::pair<std::string_view, std::string_view> split_qname(const char* qualified_name) {
  const std::string_view name(qualified_name);
  const auto colon = name.find(':');
  if (colon == std::string_view::npos) return {std::string_view{}, name};
  return {name.substr(0, colon), name.substr(colon + 1)};
}

}  // namespace

NamespaceScope::NamespaceScope(const NamespaceScope* parent, pugi::xml_node element)
    : parent_(parent) {
  for (const pugi::xml_attribute attribute : element.attributes()) {
    const std::string_view name(attribute.name());
    if (name == "xmlns") {
      bindings_.emplace_back(std::string_view{}, std::string_view(attribute.value()));
    } else if (name.substr(0, kXmlnsPrefix.size()) == kXmlnsPrefix) {
      bindings_.emplace_back(name.substr(kXmlnsPrefix.size()), std::string_view(attribute.value()));
    }
  }
}

std::vector<NamespaceScope> NamespaceScope::chain_for(pugi::xml_node element) {
  std::vector<pugi::xml_node> path;
  for (pugi::xml_node node = element; node && node.type() == pugi::node_element;
       node = node.parent()) {
    path.push_back(node);
  }
  std::vector<NamespaceScope> chain;
  chain.reserve(path.size());  // no reallocation: each scope points at the previous one
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    chain.emplace_back(chain.empty() ? nullptr : &chain.back(), *it);
  }
  return chain;
}

std::string_view NamespaceScope::uri(std::string_view prefix) const {
  for (const NamespaceScope* scope = this; scope != nullptr; scope = scope->parent_) {
    for (const auto& [bound_prefix, bound_uri] : scope->bindings_) {
      if (bound_prefix == prefix) return bound_uri;
    }
  }
  if (prefix == "xml") return kXmlNamespace;
  return {};
}

QName NamespaceScope::resolve_element(const char* qualified_name) const {
  const auto [prefix, local] = split_qname(qualified_name);
  return {uri(prefix), local};
}

QName NamespaceScope::resolve_attribute(const char* qualified_name) const {
  const auto [prefix, local] = split_qname(qualified_name);
  if (prefix.empty()) return {std::string_view{}, local};
  return {uri(prefix), local};
}

pugi::xml_attribute NamespaceScope::attribute(pugi::xml_node element, std::string_view uri_wanted,
                                              std::string_view local) const {
  for (const pugi::xml_attribute attribute : element.attributes()) {
    const char* name = attribute.name();
    // Cheap rejection before resolving the prefix.
    const std::size_t length = std::strlen(name);
    if (length < local.size() || std::string_view(name + length - local.size()) != local) continue;
    const QName qname = resolve_attribute(name);
    if (qname.local != local) continue;
    if (qname.uri == uri_wanted) return attribute;
    if (ns::is_gml(uri_wanted) && ns::is_gml(qname.uri)) return attribute;
  }
  return {};
}

namespace ns {

bool is_gml(std::string_view uri) {
  return uri == kGml || uri == kGmlOld;
}

bool is_indoorgml(std::string_view uri) {
  constexpr std::string_view kWord = "indoorgml";
  auto lower_equal = [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) == b;
  };
  return std::search(uri.begin(), uri.end(), kWord.begin(), kWord.end(), lower_equal) != uri.end();
}

}  // namespace ns
}  // namespace conicloc::io
