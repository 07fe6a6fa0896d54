// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the expressc tests.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/model.h"

namespace expressc::test {

std::string read_file(const std::filesystem::path& path);

std::filesystem::path corpus(const std::string& relative);  // tests/expressc/corpus/<relative>
std::filesystem::path reference_schema();                    // ../shared/reference/iso14649-combined.exp

// The standard part of the reference schema: its lines 1-5191, closed with END_SCHEMA.
std::string reference_standard_part();

// Compiles corpus files; fails the test (with every diagnostic) if they do not compile.
std::unique_ptr<model::Model> compile_good(const std::vector<std::string>& corpus_files);

const model::Entity& entity(const model::Model& model, const std::string& name);
const model::DefinedType& type(const model::Model& model, const std::string& name);
const model::Attribute& attribute(const model::Entity& entity, const std::string& name);

// "name" for each Part 21 slot, "name*" for a slot written as `*` (derived).
std::vector<std::string> part21_names(const model::Entity& entity);
std::vector<std::string> names(const std::vector<const model::Entity*>& entities);
std::vector<std::string> member_names(const std::vector<model::DefinedType::SelectMember>& members);

}  // namespace expressc::test
