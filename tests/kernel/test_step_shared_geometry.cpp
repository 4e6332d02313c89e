// Equal geometry written once in a STEP file (issue 14, compact files): the shapes OpenCASCADE's reader builds from
// the shared file are the shapes it builds from its own writer's file, and what is not geometry keeps its identity.
#include <gtest/gtest.h>

#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "brep/step_shared_geometry.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "test_lattices.hpp"
#include "test_support.hpp"

namespace steady {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("steady_shared_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

// OpenCASCADE's own STEP text of a shape (its writer, nothing of ours after it).
std::string occ_step_text(const TopoDS_Shape& shape) {
  const std::string path = temp_path("occ.step");
  STEPControl_Writer writer;
  EXPECT_EQ(writer.Transfer(shape, STEPControl_AsIs), IFSelect_RetDone);
  EXPECT_EQ(writer.Write(path.c_str()), IFSelect_RetDone);
  std::string text = test::file_bytes(path);
  std::remove(path.c_str());
  return text;
}

TopoDS_Shape read_step_text(const std::string& text) {
  const std::string path = temp_path("read.step");
  std::ofstream(path, std::ios::binary) << text;
  STEPControl_Reader reader;
  EXPECT_EQ(reader.ReadFile(path.c_str()), IFSelect_RetDone);
  reader.TransferRoots();
  std::remove(path.c_str());
  return reader.OneShape();
}

int count(const TopoDS_Shape& shape, TopAbs_ShapeEnum type) {
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, type, map);
  return map.Extent();
}

double volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return props.Mass();
}

int occurrences(const std::string& text, const std::string& word) {
  int n = 0;
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

TEST(StepSharedGeometry, EqualGeometryIsWrittenOnceAndReadsBackAsTheSameShape) {
  std::mt19937_64 rng(11);
  const TopoDS_Shape lattice = build_lattice_brep(flatten(test::bcc_lattice(rng, {3, 3, 3}))).shape;
  const std::string occ = occ_step_text(lattice);
  StepSharing sharing;
  const std::string shared = share_equal_geometry(occ, &sharing);
  // The BCC's hubs are translates of a few: their pcurves, in each sphere's and cone's own frame, are equal.
  EXPECT_EQ(sharing.bytes_before, occ.size());
  EXPECT_EQ(sharing.bytes_after, shared.size());
  EXPECT_LT(sharing.bytes_after, sharing.bytes_before / 2) << sharing.bytes_before << " -> " << sharing.bytes_after;
  EXPECT_LT(sharing.entities_after, sharing.entities_before * 2 / 3)
      << sharing.entities_before << " -> " << sharing.entities_after;
  EXPECT_EQ(occurrences(shared, "GEOMETRIC_REPRESENTATION_CONTEXT(2)"), 1);
  // Nothing equal is left: a second pass gives the same text.
  EXPECT_EQ(share_equal_geometry(shared), shared);

  const TopoDS_Shape a = read_step_text(occ), b = read_step_text(shared);
  for (TopAbs_ShapeEnum type : {TopAbs_SOLID, TopAbs_FACE, TopAbs_EDGE, TopAbs_VERTEX})
    EXPECT_EQ(count(b, type), count(a, type)) << "shape type " << type;
  EXPECT_EQ(count(b, TopAbs_FACE), count(lattice, TopAbs_FACE));
  EXPECT_TRUE(BRepCheck_Analyzer(b).IsValid());
  EXPECT_NEAR(volume(b), volume(a), 1e-12 * volume(a));
  EXPECT_NEAR(volume(b), volume(lattice), 1e-6 * volume(lattice));
}

// The slow twin of the sharing: records split naively, then classes of equal values merged round after round until
// nothing changes (the kernel's pass does it in one memoized walk). Returns how many entities the classes leave.
std::size_t entities_left_by_rounds(const std::string& text) {
  struct Entity {
    long id;
    std::string type, body;  // body without any whitespace outside strings
    std::vector<long> refs;
  };
  std::vector<Entity> entities;
  const std::size_t data = text.find("DATA;") + 5;
  bool in_string = false;
  std::string current;
  for (std::size_t i = data; i < text.size() && text.compare(i, 7, "ENDSEC;") != 0; ++i) {
    const char c = text[i];
    if (c == '\'') in_string = !in_string;
    if (!in_string && std::isspace(static_cast<unsigned char>(c))) continue;
    if (in_string || c != ';') {
      current += c;
      continue;
    }
    const std::size_t eq = current.find('=');
    Entity e{std::stol(current.substr(1, eq - 1)), "", current.substr(eq + 1), {}};
    e.type = e.body[0] == '(' ? (e.body.find("GEOMETRIC_REPRESENTATION_CONTEXT(2)") != std::string::npos ? "CONTEXT2D" : "")
                              : e.body.substr(0, e.body.find('('));
    bool quoted = false;
    for (std::size_t k = 0; k < e.body.size(); ++k) {
      if (e.body[k] == '\'') quoted = !quoted;
      if (!quoted && e.body[k] == '#') e.refs.push_back(std::stol(e.body.substr(k + 1)));
    }
    entities.push_back(e);
    current.clear();
  }
  const std::set<std::string> values = {"CARTESIAN_POINT", "DIRECTION", "VECTOR", "AXIS2_PLACEMENT_3D", "LINE",
                                        "CIRCLE", "ELLIPSE", "B_SPLINE_CURVE_WITH_KNOTS", "PCURVE",
                                        "DEFINITIONAL_REPRESENTATION", "SURFACE_CURVE", "SEAM_CURVE", "CONTEXT2D"};
  const std::set<std::string> geometry = {"VERTEX_POINT", "EDGE_CURVE", "ORIENTED_EDGE", "EDGE_LOOP", "FACE_BOUND",
                                          "FACE_OUTER_BOUND", "ADVANCED_FACE", "PLANE", "CYLINDRICAL_SURFACE",
                                          "CONICAL_SURFACE", "SPHERICAL_SURFACE", "TOROIDAL_SURFACE"};
  std::set<long> pinned;
  for (const Entity& e : entities)
    if (!values.count(e.type) && !geometry.count(e.type)) pinned.insert(e.refs.begin(), e.refs.end());
  std::map<long, long> cls;
  for (const Entity& e : entities) cls[e.id] = e.id;
  for (bool changed = true; changed;) {
    changed = false;
    std::map<std::string, long> first;
    for (const Entity& e : entities) {
      if (!values.count(e.type) || pinned.count(e.id)) continue;
      // The value: the body with its reference numbers blanked, then the classes they refer to.
      std::string blanked;
      bool q = false;
      for (std::size_t k = 0; k < e.body.size(); ++k) {
        if (e.body[k] == '\'') q = !q;
        if (!q && e.body[k] == '#') {
          blanked += '#';
          while (k + 1 < e.body.size() && std::isdigit(static_cast<unsigned char>(e.body[k + 1]))) ++k;
        } else {
          blanked += e.body[k];
        }
      }
      std::string signature = blanked;
      for (long r : e.refs) signature += " " + std::to_string(cls.at(r));
      const long representative = first.emplace(signature, e.id).first->second;
      if (cls[e.id] != representative) {
        cls[e.id] = representative;
        changed = true;
      }
    }
  }
  std::set<long> classes;
  for (const Entity& e : entities) classes.insert(cls[e.id]);
  return classes.size();
}

TEST(StepSharedGeometry, TheSharedFileKeepsAsManyEntitiesAsMergingRoundByRoundAndIgnoresLayout) {
  std::mt19937_64 rng(23);
  const std::string occ = occ_step_text(build_lattice_brep(flatten(test::bcc_lattice(rng, {2, 2, 2}))).shape);
  StepSharing sharing;
  const std::string shared = share_equal_geometry(occ, &sharing);
  EXPECT_EQ(sharing.entities_after, entities_left_by_rounds(occ));
  // The same records laid out otherwise (spaces, line breaks and comments after commas) share alike.
  std::string relaid;
  std::uniform_int_distribution<int> pick(0, 3);
  const char* const layouts[] = {"", " ", "\n   ", " /* a comment, with ';' */ "};
  bool quoted = false;
  const std::size_t data = occ.find("DATA;");
  for (std::size_t i = 0; i < occ.size(); ++i) {
    relaid += occ[i];
    if (occ[i] == '\'') quoted = !quoted;
    if (i > data && !quoted && occ[i] == ',') relaid += layouts[pick(rng)];
  }
  ASSERT_NE(relaid, occ);
  EXPECT_EQ(share_equal_geometry(relaid), shared);
}

// The rule on a small file: points and directions are shared, but the two placements a shape representation lists
// (an assembly's frames, a set of items) stay two; strings keep their '#', ';' and quotes.
TEST(StepSharedGeometry, ValuesThatARepresentationListsKeepTheirOwnEntities) {
  const std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_NAME('DATA;#1','',(''),(''),'','','');\nENDSEC;\nDATA;\n"
      "#10 = SHAPE_REPRESENTATION('a;#3 ''q''',(#20,#50),#90);\n"
      "#20 = AXIS2_PLACEMENT_3D('',#30,#40,#41);\n#30 = CARTESIAN_POINT('',(0.,0.,0.));\n"
      "#40 = DIRECTION('',(0.,0.,1.));\n#41 = DIRECTION('',(1.,0.,0.));\n"
      "#50 = AXIS2_PLACEMENT_3D('',#60,#70,#71);\n#60 = CARTESIAN_POINT('',(0.,0.,0.));\n"
      "#70 = DIRECTION('',(0.,0.,1.));\n#71 = DIRECTION('',(1.,0.,0.));\n"
      "#90 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) \nREPRESENTATION_CONTEXT('x','y') );\nENDSEC;\nEND-ISO-10303-21;\n";
  const std::string shared = share_equal_geometry(text);
  EXPECT_EQ(occurrences(shared, "AXIS2_PLACEMENT_3D("), 2);
  EXPECT_EQ(occurrences(shared, "CARTESIAN_POINT("), 1);
  EXPECT_EQ(occurrences(shared, "DIRECTION("), 2);
  EXPECT_NE(shared.find("#1=SHAPE_REPRESENTATION('a;#3 ''q''',(#2,#6),#7);"), std::string::npos) << shared;
  EXPECT_NE(shared.find("#2=AXIS2_PLACEMENT_3D('',#3,#4,#5);"), std::string::npos) << shared;
  EXPECT_NE(shared.find("#6=AXIS2_PLACEMENT_3D('',#3,#4,#5);"), std::string::npos) << shared;
  EXPECT_NE(shared.find("#7=(GEOMETRIC_REPRESENTATION_CONTEXT(3) REPRESENTATION_CONTEXT('x','y'));"), std::string::npos)
      << shared;
  // The header is copied as it is: its "DATA;" inside a string does not start the DATA section.
  EXPECT_NE(shared.find("FILE_NAME('DATA;#1','',"), std::string::npos);
  const std::string end = "\nENDSEC;\nEND-ISO-10303-21;\n";
  EXPECT_EQ(shared.substr(shared.size() - end.size()), end);
}

TEST(StepSharedGeometry, TextThatIsNotAWritersDataSectionIsAnError) {
  const std::string head = "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n";
  for (const std::string& bad : {std::string("ISO-10303-21;\nHEADER;\nENDSEC;\n"),            // no DATA
                                 head + "#1=CARTESIAN_POINT('',(0.,0.,0.))",                 // no ';', no ENDSEC
                                 head + "#1=VECTOR('',#7,1.);\nENDSEC;\n",                   // #7 undefined
                                 head + "#1=LINE('',#1,#1);\n#1=LINE('',#1,#1);\nENDSEC;\n",  // #1 twice
                                 head + "#1=CARTESIAN_POINT('x,(0.,0.,0.));\nENDSEC;\n",     // open string
                                 head + "X=1;\nENDSEC;\n",
                                 head + "#1=VECTOR('',#,1.);\nENDSEC;\n",                      // '#' alone
                                 head + "#1=VECTOR('',#1234567890123456789,1.);\nENDSEC;\n",  // 19 digits
                                 head + "#99999999=CARTESIAN_POINT('',(0.,0.));\nENDSEC;\n"})  // far numbers
    EXPECT_THROW(share_equal_geometry(bad), std::runtime_error) << bad;
}

// Through the kernel's writer and reader process: names with STEP's separators and quotes, and a part placed three
// times (its placements are values an assembly lists), come back as written.
TEST(StepSharedGeometry, TheAssemblyWriterKeepsNamesAndPlacedCopies) {
  StepPart odd{"hub #1; 'beam' (a)", BRepPrimAPI_MakeBox(1.0, 2.0, 3.0).Shape()};
  StepPart rod{"rod", BRepPrimAPI_MakeBox(0.5, 0.5, 4.0).Shape()};
  for (int i = 0; i < 3; ++i) {
    gp_Trsf t;
    t.SetTranslation(gp_Vec(5.0 * (i + 1), 0.0, 0.0));
    rod.instances.push_back(t);
  }
  const std::string path = temp_path("assembly.step");
  write_step_assembly(path, {odd, rod});
  const std::vector<StepPart> back = read_step_parts(path);
  std::remove(path.c_str());
  ASSERT_EQ(back.size(), 4u);
  EXPECT_EQ(back[0].name, odd.name);
  EXPECT_NEAR(volume(back[0].shape), 6.0, 1e-9);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(back[1 + i].name, "rod");
    GProp_GProps props;
    BRepGProp::VolumeProperties(back[1 + i].shape, props);
    EXPECT_NEAR(props.CentreOfMass().X(), 5.0 * (i + 1) + 0.25, 1e-9) << "copy " << i;
    EXPECT_NEAR(props.Mass(), 1.0, 1e-9);
  }
}

}  // namespace
}  // namespace steady
