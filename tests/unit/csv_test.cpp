// CSV tables: fixed schema, quoting, infinities written as `inf`, and NaNs written as
// empty cells but counted, never silently.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "reports/csv.h"

namespace cbr::reports {
namespace {

TEST(Csv, NumbersInfinitiesAndQuoting) {
    CsvTable t({"name", "value"});
    t.addRow({{"name", "a,b"}, {"value", 1.5}});
    t.addRow({{"name", "say \"hi\""}, {"value", INFINITY}});
    t.addRow({{"name", "empty"}});
    EXPECT_EQ(t.str(), "name,value\n\"a,b\",1.5\n\"say \"\"hi\"\"\",inf\nempty,\n");
    EXPECT_EQ(t.nanCells(), 0u);
}

TEST(Csv, NaNBecomesAnEmptyCellAndIsCounted) {
    CsvTable t({"name", "value"});
    t.addRow({{"name", "x"}, {"value", std::nan("")}});
    t.addRow({{"name", "y"}, {"value", 2.0}});
    EXPECT_EQ(t.str(), "name,value\nx,\ny,2\n");
    ASSERT_EQ(t.nanCells(), 1u);
    EXPECT_EQ(t.nanWhere().front(), "value@1");
}

TEST(Csv, UnknownColumnIsAProgrammingError) {
    CsvTable t({"name"});
    EXPECT_THROW(t.addRow({{"nmae", "typo"}}), std::logic_error);
}

}  // namespace
}  // namespace cbr::reports
