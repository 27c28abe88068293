#include "bhnsid/core/yaml_tree.hpp"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <fstream>
#include <set>
#include <sstream>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::core {

std::string TextPos::str() const {
  if (line <= 0) return source;
  return fmt::format("{}:{}:{}", source, line, column);
}

const char* YamlNode::kind_name() const {
  switch (kind) {
    case Kind::null: return "nothing";
    case Kind::scalar: return "a scalar";
    case Kind::sequence: return "a list";
    case Kind::map: return "a mapping";
  }
  return "?";
}

namespace {

// Builds the tree from parser events. Depth is checked as containers open, before yaml-cpp
// recurses further, so a 10,000-deep input stops at yaml_max_depth.
class TreeBuilder : public YAML::EventHandler {
 public:
  explicit TreeBuilder(std::string source) : source_(std::move(source)) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    check_anchor(mark, anchor);
    YamlNode node;
    node.pos = pos(mark);
    add(std::move(node));
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override {
    throw InputError(fmt::format("{}: YAML aliases are not supported in parameter files", pos(mark).str()));
  }
  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    check_anchor(mark, anchor);
    YamlNode node;
    node.kind = YamlNode::Kind::scalar;
    node.scalar = value;
    node.plain = (tag != "!");
    node.pos = pos(mark);
    add(std::move(node));
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor, YamlNode::Kind::sequence);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, anchor, YamlNode::Kind::map);
  }
  void OnMapEnd() override { close(); }

  bool has_root() const { return has_root_; }
  YamlNode take_root() { return std::move(root_); }

 private:
  TextPos pos(const YAML::Mark& mark) const { return TextPos{source_, mark.line + 1, mark.column + 1}; }

  void check_anchor(const YAML::Mark& mark, YAML::anchor_t anchor) const {
    if (anchor != YAML::NullAnchor)
      throw InputError(fmt::format("{}: YAML anchors are not supported in parameter files", pos(mark).str()));
  }

  void open(const YAML::Mark& mark, YAML::anchor_t anchor, YamlNode::Kind kind) {
    check_anchor(mark, anchor);
    if (static_cast<int>(stack_.size()) >= yaml_max_depth)
      throw InputError(fmt::format("{}: nesting deeper than {} levels; a parameter file needs at most a few",
                                   pos(mark).str(), yaml_max_depth));
    Frame frame;
    frame.node.kind = kind;
    frame.node.pos = pos(mark);
    stack_.push_back(std::move(frame));
  }

  void close() {
    YamlNode node = std::move(stack_.back().node);
    stack_.pop_back();
    add(std::move(node));
  }

  // Map children alternate key, value; a key waits in its frame until its value arrives.
  void add(YamlNode node) {
    if (stack_.empty()) {
      if (has_root_) throw InputError(fmt::format("{}: more than one YAML document", node.pos.str()));
      root_ = std::move(node);
      has_root_ = true;
      return;
    }
    Frame& frame = stack_.back();
    YamlNode& parent = frame.node;
    if (parent.kind == YamlNode::Kind::sequence) {
      parent.items.push_back(std::move(node));
      return;
    }
    if (!frame.has_key) {
      if (node.kind != YamlNode::Kind::scalar)
        throw InputError(fmt::format("{}: a key must be a plain name, got {}", node.pos.str(), node.kind_name()));
      for (const auto& [key, value] : parent.entries)
        if (key.scalar == node.scalar)
          throw InputError(fmt::format("{}: duplicate key '{}' (first given at line {})", node.pos.str(),
                                       node.scalar, key.pos.line));
      frame.key = std::move(node);
      frame.has_key = true;
      return;
    }
    parent.entries.emplace_back(std::move(frame.key), std::move(node));
    frame.has_key = false;
  }

  struct Frame {
    YamlNode node;
    YamlNode key;
    bool has_key = false;
  };
  std::string source_;
  std::vector<Frame> stack_;
  YamlNode root_;
  bool has_root_ = false;
};

}  // namespace

YamlNode parse_yaml(const std::string& text, const std::string& source) {
  if (text.size() > yaml_max_bytes)
    throw InputError(fmt::format("{}: {} bytes is too large for a parameter file (limit {})", source,
                                 text.size(), yaml_max_bytes));
  std::istringstream stream(text);
  TreeBuilder builder(source);
  try {
    YAML::Parser parser(stream);
    if (parser.HandleNextDocument(builder) && parser.HandleNextDocument(builder))
      throw InputError(fmt::format("{}: more than one YAML document ('---')", source));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}:{}:{}: YAML syntax error: {}", source, e.mark.line + 1, e.mark.column + 1,
                                 e.msg));
  }
  if (!builder.has_root()) return YamlNode{YamlNode::Kind::null, {}, true, {}, {}, TextPos{source, 1, 1}};
  return builder.take_root();
}

YamlNode read_yaml_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(fmt::format("{}: no such file", name));
  if (std::filesystem::is_directory(path, ec)) throw InputError(fmt::format("{}: is a directory, expected a parameter file", name));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot be read (permission denied?)", name));
  std::string text;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > yaml_max_bytes)
      throw InputError(fmt::format("{}: larger than {} bytes, too large for a parameter file", name, yaml_max_bytes));
  }
  if (in.bad()) throw InputError(fmt::format("{}: read error", name));
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(fmt::format("{}: the file is empty; expected a parameter file with a 'plugins:' list", name));
  return parse_yaml(text, name);
}

}  // namespace bhnsid::core
