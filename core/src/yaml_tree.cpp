#include "bhnsid/core/yaml_tree.hpp"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <sstream>
#include <unordered_map>

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
    // yaml-cpp reports "?" for an untagged plain scalar and "!" for a quoted one.
    if (tag != "?" && tag != "!") refuse_tag(mark, tag);
    node.scalar = value;
    node.plain = (tag != "!");
    node.pos = pos(mark);
    add(std::move(node));
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    if (tag != "?" && !tag.empty()) refuse_tag(mark, tag);
    open(mark, anchor, YamlNode::Kind::sequence);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    if (tag != "?" && !tag.empty()) refuse_tag(mark, tag);
    open(mark, anchor, YamlNode::Kind::map);
  }
  void OnMapEnd() override { close(); }

  bool has_root() const { return has_root_; }
  YamlNode take_root() { return std::move(root_); }

 private:
  TextPos pos(const YAML::Mark& mark) const { return TextPos{source_, mark.line + 1, mark.column + 1}; }

  // A tag asks for an interpretation (!!str, !!float, a custom type) that we would otherwise drop
  // silently; the value's type comes from the parameter's declaration alone.
  [[noreturn]] void refuse_tag(const YAML::Mark& mark, const std::string& tag) const {
    std::string shown = tag.rfind("tag:yaml.org,2002:", 0) == 0 ? "!!" + tag.substr(18) : tag;
    if (shown.size() > 40) shown = shown.substr(0, 40) + "...";
    throw InputError(fmt::format("{}: YAML tag '{}' is not interpreted in parameter files; remove it (quote a value "
                                 "to make it a string)",
                                 pos(mark).str(), shown));
  }

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
      if (node.scalar.size() > yaml_max_key_length)
        throw InputError(fmt::format("{}: a key of {} characters ('{}...'); names of sections and parameters are at "
                                     "most {} characters",
                                     node.pos.str(), node.scalar.size(), node.scalar.substr(0, 24),
                                     yaml_max_key_length));
      // One hash lookup per key keeps a file of many keys linear in its size.
      const auto [first, inserted] = frame.lines.emplace(node.scalar, node.pos.line);
      if (!inserted)
        throw InputError(fmt::format("{}: duplicate key '{}' (first given at line {})", node.pos.str(),
                                     node.scalar, first->second));
      frame.key = std::move(node);
      frame.has_key = true;
      return;
    }
    parent.entries.push_back(YamlEntry{std::move(frame.key), std::move(node)});
    frame.has_key = false;
  }

  struct Frame {
    YamlNode node;
    YamlNode key;
    bool has_key = false;
    std::unordered_map<std::string, int> lines;  ///< keys seen so far in this map, with their lines
  };
  std::string source_;
  std::vector<Frame> stack_;
  YamlNode root_;
  bool has_root_ = false;
};

// yaml-cpp's messages for a tab in the indentation or an overlong key say neither; name the first
// such line at or before the error.
std::string tab_hint(const std::string& text, int error_line) {
  int line = 0;
  for (std::size_t start = 0; start < text.size() && line <= error_line; ++line) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::size_t indent_end = std::min(text.find_first_not_of(" \t", start), end);
    if (text.compare(start, indent_end - start, std::string(indent_end - start, ' ')) != 0)
      return fmt::format(" (line {} is indented with a tab; YAML indents with spaces only)", line + 1);
    // yaml-cpp refuses implicit keys over 1024 characters with "illegal map value".
    const std::size_t colon = line == error_line ? text.find(':', indent_end) : std::string::npos;
    if (colon < end && colon - indent_end > 1024)
      return fmt::format(" (line {} starts with a key of {} characters; names of sections and parameters are at "
                         "most {})",
                         line + 1, colon - indent_end, yaml_max_key_length);
    start = end + 1;
  }
  return {};
}

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
    throw InputError(fmt::format("{}:{}:{}: YAML syntax error: {}{}", source, e.mark.line + 1, e.mark.column + 1,
                                 e.msg, tab_hint(text, e.mark.line)));
  }
  if (!builder.has_root()) return YamlNode{YamlNode::Kind::null, {}, true, {}, {}, TextPos{source, 1, 1}};
  return builder.take_root();
}

std::string read_parfile_text(const std::filesystem::path& path) {
  const std::string name = path.string();
  // O_NONBLOCK so that opening a FIFO cannot wait for a writer; fstat on the open descriptor then
  // decides, with no window between the check and the read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT) throw InputError(fmt::format("{}: no such file", name));
    if (error == EACCES) throw InputError(fmt::format("{}: cannot be read (permission denied)", name));
    throw InputError(fmt::format("{}: cannot be opened: {}", name, std::strerror(error)));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw InputError(fmt::format("{}: cannot be examined: {}", name, std::strerror(errno)));
  if (S_ISDIR(st.st_mode)) throw InputError(fmt::format("{}: is a directory, expected a parameter file", name));
  if (!S_ISREG(st.st_mode))
    throw InputError(fmt::format("{}: is not a regular file (a FIFO, socket or device); expected a parameter file "
                                 "on disk",
                                 name));
  if (static_cast<std::uint64_t>(st.st_size) > yaml_max_bytes)
    throw InputError(fmt::format("{}: larger than {} bytes, too large for a parameter file", name, yaml_max_bytes));
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  std::string text;
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(fmt::format("{}: read error: {}", name, std::strerror(errno)));
    }
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > yaml_max_bytes)
      throw InputError(fmt::format("{}: larger than {} bytes, too large for a parameter file", name, yaml_max_bytes));
  }
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(fmt::format("{}: the file is empty; expected a parameter file with a 'plugins:' list", name));
  return text;
}

YamlNode read_yaml_file(const std::filesystem::path& path) { return parse_yaml(read_parfile_text(path), path.string()); }

}  // namespace bhnsid::core
