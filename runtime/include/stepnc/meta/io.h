// SPDX-License-Identifier: Apache-2.0
/// @file
/// Part 21 input and output of typed instances, generic through the
/// metaclass tables.
///
/// Writing is done here once, by reflection, rather than by a generated
/// write function per entity: the tables already hold everything a record
/// needs (attribute order, types, select member names), one loop serves
/// every schema, generated code stays small (build time), and the cost per
/// value is an indirect call next to number formatting, which dominates.
///
/// Reading is split the way the Part 21 layer reads files: the caller
/// creates every instance first (Registry + EntityInfo::create, with the
/// file's ids) so that forward references resolve, then fills each one from
/// its parsed record with fill_instance(). A caller that creates and fills
/// each instance as it reads instead defers forward references
/// (FillContext::defer) and binds them at the end (bind_reference).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/meta/info.h"
#include "stepnc/meta/model.h"
#include "stepnc/meta/value.h"
#include "stepnc/p21/parameters.h"
#include "stepnc/p21/writer.h"

namespace stepnc::meta {

// ---------------------------------------------------------------- writing

/// Writes `instance` as one record: `#id=NAME(...);`, or for a complex
/// (ANDOR) instance `#id=(A(...)B(...));` with every entity of the
/// combination in alphabetical order, each with the attributes it declares.
void write_instance(const Instance& instance, p21::Writer& writer);

/// Writes one value (a stored attribute or an aggregate element).
void write_value(const ValueRef& value, p21::Writer& writer);

/// The header of a file written from a model.
struct FileHeader {
  std::vector<std::string> description;  ///< FILE_DESCRIPTION description
  std::string implementation_level = "2;1";  ///< FILE_DESCRIPTION implementation level
  std::string name;  ///< FILE_NAME name
  std::string time_stamp;  ///< FILE_NAME time stamp (ISO 8601)
  std::vector<std::string> author;  ///< FILE_NAME author
  std::vector<std::string> organization;  ///< FILE_NAME organization
  std::string preprocessor_version;  ///< FILE_NAME preprocessor version
  std::string originating_system;  ///< FILE_NAME originating system
  std::string authorization;  ///< FILE_NAME authorization
  std::vector<std::string> schemas;  ///< FILE_SCHEMA
};

/// The whole file: header, then every instance in increasing id order,
/// formatted on `jobs` threads (p21::write_in_parts: the same bytes for any
/// number; 0 is the core count for large models).
void write_model(const Model& model, const FileHeader& header, p21::Writer& writer, unsigned jobs = 1);
/// The whole file as text (see write_model()).
std::string to_text(const Model& model, const FileHeader& header, unsigned jobs = 1);
/// Writes safely (stepnc/io/output.h: atomic for files, `-` is stdout);
/// returns an error message on failure.
std::optional<std::string> write_file(const Model& model, const FileHeader& header,
                                      const std::filesystem::path& path, unsigned jobs = 1);

// ---------------------------------------------------------------- reading

/// A reference fill_instance() left unbound because the context deferred
/// it: a reader that creates instances as it goes meets forward references
/// before their targets exist. Its slot stays valid while the instance does
/// (fill_instance() sizes each aggregate once).
struct PendingReference {
  ValueRef target;  ///< the attribute or element slot: an entity or a SELECT
  const AttributeInfo* attribute = nullptr;  ///< the attribute it belongs to
  std::uint64_t id = 0;      ///< the `#id` referred to
  std::uint64_t offset = 0;  ///< of the reference in the file
};

/// What fill_instance() needs from the reader around it.
class FillContext {
 public:
  virtual ~FillContext() = default;
  /// The instance with Part 21 id `id`, or null if the file has none.
  virtual Instance* resolve(std::uint64_t id) = 0;
  /// Called when resolve() returned null. Returning true takes the
  /// reference over (to bind later with bind_reference()); false reports
  /// the instance as missing now.
  virtual bool defer(const PendingReference& /*reference*/) { return false; }
  /// A problem with the value at absolute file offset `offset`.
  virtual void error(std::uint64_t offset, std::string message) = 0;
  /// Why `#id` has no instance, for the message of a reference to it (a
  /// reader knows when the file has the record but kept it untyped).
  virtual std::string describe_missing(std::uint64_t id);
};

/// Sets the explicit attributes of `instance` from a parsed record (`record`
/// must hold one record whose entity, or complex parts, match the instance's
/// EntityInfo). Every problem is reported to `context`, and reading goes on
/// with the next attribute: a wrong attribute count, a value of the wrong
/// kind, a missing or wrongly typed reference, a missing required value, an
/// aggregate outside its bounds, an unknown enumeration item. Returns the
/// number of problems reported.
std::size_t fill_instance(Instance& instance, const p21::ParamTree& record, FillContext& context);

/// Binds a deferred reference to `instance` (null: the file has no such
/// instance). Returns the problem, worded as fill_instance() reports it,
/// when the instance is missing or of a type the slot does not allow.
std::optional<std::string> bind_reference(const PendingReference& reference, Instance* instance);

// ---------------------------------------------------------------- inspection

/// Every explicit attribute of `instance` through reflection, one per line:
///   `#12`=cartesian_point (machining_schema)
///     name: ''
///     coordinates: (0.,0.,10.)
/// Values use Part 21 spelling; unset optionals show as `$`. Derived
/// attributes the class computes follow, marked `(derived)`.
std::string dump(const Instance& instance);

/// One attribute as dump() shows it.
struct AttributeText {
  std::string_view name;  ///< the attribute's EXPRESS name
  std::string value;      ///< Part 21 spelling; `$` when unset
  bool derived = false;   ///< a DERIVE attribute the class computes
};
/// The attributes dump() shows, for callers that lay them out themselves
/// (the CLI's JSON): explicit ones in Part 21 spelling, then derived ones.
std::vector<AttributeText> attribute_texts(const Instance& instance);

}  // namespace stepnc::meta
