// SPDX-License-Identifier: Apache-2.0
// The compiler driver: parse every source, resolve, sort the diagnostics.
#include <algorithm>
#include <tuple>

#include "model/model.h"
#include "model/resolver.h"
#include "parser/parser.h"
#include "stepnc/io/input.h"

namespace expressc::model {

namespace {

// The syntax trees, kept alive by Model::syntax for the expressions the
// model points into.
struct SyntaxTrees {
  std::vector<ast::SourceFile> files;
};

// In input file order, then by position.
void sort_diagnostics(std::vector<Diagnostic>& diagnostics, const std::vector<SourceText>& sources) {
  auto file_rank = [&](const std::string& file) {
    auto it = std::find_if(sources.begin(), sources.end(), [&](const SourceText& s) { return s.name == file; });
    return static_cast<size_t>(it - sources.begin());
  };
  std::stable_sort(diagnostics.begin(), diagnostics.end(), [&](const Diagnostic& a, const Diagnostic& b) {
    return std::make_tuple(file_rank(a.file), a.line, a.column) < std::make_tuple(file_rank(b.file), b.line, b.column);
  });
}

}  // namespace

CompileResult compile(std::vector<SourceText> sources) {
  CompileResult result;
  auto model = std::make_unique<Model>();
  auto trees = std::make_shared<SyntaxTrees>();
  trees->files.reserve(sources.size());

  for (const SourceText& source : sources) {
    parser::ParseResult parsed = parser::parse(source.name, source.text);
    for (const parser::SyntaxError& error : parsed.errors)
      result.diagnostics.push_back(
          {Diagnostic::Severity::Error, source.name, error.position.line, error.position.column, error.message});
    trees->files.push_back(std::move(parsed.file));
    model->files.push_back(std::make_unique<std::string>(source.name));
  }

  // Names can only be resolved in syntactically complete sources.
  if (result.diagnostics.empty()) {
    std::vector<const ast::SourceFile*> files;
    for (const ast::SourceFile& file : trees->files) files.push_back(&file);
    detail::Reporter reporter(result.diagnostics);
    detail::resolve(*model, files, reporter);
  }

  sort_diagnostics(result.diagnostics, sources);
  model->syntax = std::move(trees);
  const bool failed = std::any_of(result.diagnostics.begin(), result.diagnostics.end(),
                                  [](const Diagnostic& d) { return d.severity == Diagnostic::Severity::Error; });
  if (!failed) result.model = std::move(model);
  return result;
}

CompileResult compile_files(std::span<const std::filesystem::path> files) {
  std::vector<SourceText> sources;
  std::vector<Diagnostic> unreadable;
  for (const std::filesystem::path& path : files) {
    // `-`: standard input, as for every stepnc tool.
    const std::string name = stepnc::io::is_standard_stream(path) ? stepnc::io::standard_input_name : path.string();
    std::string text;
    if (auto error = stepnc::io::read_text(path, text)) {
      unreadable.push_back({Diagnostic::Severity::Error, name, 0, 0, *error});
      continue;
    }
    sources.push_back({name, std::move(text)});
  }
  if (!unreadable.empty()) return {nullptr, std::move(unreadable)};
  return compile(std::move(sources));
}

}  // namespace expressc::model
