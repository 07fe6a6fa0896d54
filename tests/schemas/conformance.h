// Checks the instances of a Part 21 file against a compiled schema model,
// so that hand-written samples stay valid as the schemas evolve.
//
// Checked: every entity name is declared and, for simple instances, not
// abstract; each record has as many parameters as the entity's Part 21
// slots; `$` only for OPTIONAL attributes and `*` exactly for derived ones;
// every value fits its attribute's type (simple kinds, enumeration items,
// aggregate bounds and elements, typed values and references for SELECTs,
// references to instances of the required entity or a subtype).
// Not checked: WHERE, UNIQUE and global rules, which need an evaluator.
#pragma once

#include <string>
#include <vector>

#include "model/model.h"
#include "stepnc/p21/document.h"

namespace stepnc::schema_test {

// One message per violation, e.g. "#42 BIDIRECTIONAL_MILLING.feed_direction:
// #43 is a CARTESIAN_POINT, not a direction". Empty when the file conforms.
std::vector<std::string> conformance_errors(const expressc::model::Model& model,
                                            const p21::Document& document);

}  // namespace stepnc::schema_test
