#pragma once
// XML namespace resolution on top of pugixml, which keeps prefixes as written: a scope maps each
// prefix bound by xmlns attributes of an element and its ancestors to its URI, so elements are
// matched by (namespace URI, local name) whatever prefix a file happens to use.

#include <pugixml.hpp>
#include <string_view>
#include <utility>
#include <vector>

namespace conicloc::io {

struct QName {
  std::string_view uri;    ///< empty when the name is in no namespace
  std::string_view local;  ///< name without prefix
};

/// The namespace bindings in force at one element. Scopes form a chain up to the root; a child
/// scope only holds the bindings its element adds, so building one per element is cheap.
/// Precondition: the parent scope and the document outlive this scope (views into its buffer).
class NamespaceScope {
 public:
  /// Scope of `element` given the scope of its parent (nullptr at the root).
  NamespaceScope(const NamespaceScope* parent, pugi::xml_node element);

  /// Scope of any element, built by walking its ancestors (for xlink targets).
  static std::vector<NamespaceScope> chain_for(pugi::xml_node element);

  /// URI bound to `prefix` ("" = default namespace); empty view when unbound.
  std::string_view uri(std::string_view prefix) const;

  /// Element or attribute name resolved. Attributes without a prefix are in no namespace.
  QName resolve_element(const char* qualified_name) const;
  QName resolve_attribute(const char* qualified_name) const;

  /// First attribute of `element` with this namespace URI and local name (empty uri: no namespace).
  pugi::xml_attribute attribute(pugi::xml_node element, std::string_view uri,
                                std::string_view local) const;

 private:
  const NamespaceScope* parent_ = nullptr;
  std::vector<std::pair<std::string_view, std::string_view>> bindings_;  // prefix -> uri
};

namespace ns {
inline constexpr std::string_view kGml = "http://www.opengis.net/gml/3.2";
inline constexpr std::string_view kGmlOld = "http://www.opengis.net/gml";
inline constexpr std::string_view kXlink = "http://www.w3.org/1999/xlink";
/// GML 3.2 or the older GML 3.1 namespace.
bool is_gml(std::string_view uri);
/// Any IndoorGML namespace (core, navigation, 1.0 or 2.0 and drafts): the URI names "indoorgml".
bool is_indoorgml(std::string_view uri);
}  // namespace ns

}  // namespace conicloc::io
