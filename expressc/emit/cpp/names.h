// SPDX-License-Identifier: Apache-2.0
// C++ names for EXPRESS identifiers: the EXPRESS spelling, with a trailing
// underscore where it would clash with C++, its library macros or the runtime.
#pragma once

#include <string>
#include <string_view>

namespace expressc::emit::cpp {

// A type, namespace or enumerator name (C++ keywords and standard library
// macros get a trailing _).
std::string identifier(std::string_view name);
// A member name of a generated entity class: also avoids the members every
// class has (id, object, entity_info, meta_entity...).
std::string member_identifier(std::string_view name);
// An entity name as Part 21 spells it (upper case), emitted once into the
// tables so that writers need not convert it per record.
std::string p21_name(std::string_view name);

}  // namespace expressc::emit::cpp
