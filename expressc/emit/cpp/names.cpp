// SPDX-License-Identifier: Apache-2.0
#include "emit/cpp/names.h"

#include <set>

namespace expressc::emit::cpp {

namespace {

// C++ keywords and alternative tokens that are valid EXPRESS identifiers.
const std::set<std::string_view> kCppKeywords = {
    "alignas", "alignof", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
    "char", "char8_t", "char16_t", "char32_t", "class", "co_await", "co_return", "co_yield",
    "compl", "concept", "const", "const_cast", "consteval", "constexpr", "constinit", "continue",
    "decltype", "default", "delete", "do", "double", "dynamic_cast", "explicit", "export",
    "extern", "float", "friend", "goto", "inline", "int", "long", "mutable", "namespace", "new",
    "noexcept", "not_eq", "nullptr", "operator", "or_eq", "private", "protected", "public",
    "register", "reinterpret_cast", "requires", "short", "signed", "sizeof", "static",
    "static_assert", "static_cast", "struct", "switch", "template", "this", "thread_local",
    "throw", "try", "typedef", "typeid", "typename", "union", "unsigned", "using", "virtual",
    "void", "volatile", "wchar_t", "while", "xor_eq", "and_eq", "int8_t", "int16_t", "int32_t",
    "int64_t", "uint8_t", "uint16_t", "uint32_t", "uint64_t", "size_t", "std", "stepnc"};

// Macros of the C and C++ standard libraries (and the GNU predefined ones)
// that a generated file may see through its includes: an EXPRESS name spelled
// like one would be replaced by the preprocessor (IFC4's IfcNullStyle has the
// enumeration item NULL). Only names EXPRESS can spell: no leading underscore.
const std::set<std::string_view> kLibraryMacros = {
    "NULL", "EOF", "BUFSIZ", "FILENAME_MAX", "FOPEN_MAX", "TMP_MAX", "L_tmpnam", "SEEK_SET",
    "SEEK_CUR", "SEEK_END", "stdin", "stdout", "stderr", "errno", "EDOM", "ERANGE", "EILSEQ",
    "assert", "offsetof", "setjmp", "va_arg", "va_copy", "va_end", "va_start", "CHAR_BIT",
    "MB_LEN_MAX", "EXIT_SUCCESS", "EXIT_FAILURE", "RAND_MAX", "MB_CUR_MAX", "CLOCKS_PER_SEC",
    "HUGE_VAL", "HUGE_VALF", "HUGE_VALL", "INFINITY", "NAN", "FP_INFINITE", "FP_NAN", "FP_NORMAL",
    "FP_SUBNORMAL", "FP_ZERO", "math_errhandling", "MATH_ERRNO", "MATH_ERREXCEPT", "SIGABRT",
    "SIGFPE", "SIGILL", "SIGINT", "SIGSEGV", "SIGTERM", "SIG_DFL", "SIG_ERR", "SIG_IGN", "LC_ALL",
    "LC_COLLATE", "LC_CTYPE", "LC_MONETARY", "LC_NUMERIC", "LC_TIME", "linux", "unix"};

// Names every generated entity class already has (from meta::Instance or
// the generator); an attribute with one of these names gets a trailing _.
const std::set<std::string_view> kReservedMembers = {"id", "object", "entity_info", "meta_entity",
                                                     "meta_entity_is_abstract"};

}  // namespace

std::string identifier(std::string_view name) {
  std::string id(name);
  if (kCppKeywords.count(id) != 0 || kLibraryMacros.count(id) != 0) id += '_';
  return id;
}

std::string p21_name(std::string_view name) {
  std::string spelled(name);
  for (char& c : spelled)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return spelled;
}

std::string member_identifier(std::string_view name) {
  std::string id = identifier(name);
  if (kReservedMembers.count(id) != 0) id += '_';
  return id;
}

}  // namespace expressc::emit::cpp
