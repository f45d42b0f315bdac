#include "MeshIO.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

namespace gs
{

namespace
{
// Reads the next non-empty, non-comment token line of an OFF file.
bool NextDataLine(std::istream& in, std::string& line)
{
  while (std::getline(in, line))
  {
    const auto hash = line.find('#');
    if (hash != std::string::npos)
    {
      line.erase(hash);
    }
    if (line.find_first_not_of(" \t\r\n") != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

void AddPolygon(TriangleSoup& soup, const std::vector<long long>& poly)
{
  for (std::size_t k = 1; k + 1 < poly.size(); ++k)
  {
    soup.Triangles.push_back({ poly[0], poly[k], poly[k + 1] });
  }
}
} // namespace

bool ReadOFF(const std::string& path, TriangleSoup& soup, std::string& error)
{
  soup = TriangleSoup();
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot open " + path;
    return false;
  }
  std::string line;
  if (!NextDataLine(in, line))
  {
    error = path + " is empty";
    return false;
  }
  std::istringstream header(line);
  std::string magic;
  header >> magic;
  long long nv = -1, nf = -1, ne = 0;
  if (magic.size() >= 3 && magic.compare(magic.size() - 3, 3, "OFF") == 0)
  {
    if (!(header >> nv >> nf >> ne))
    {
      if (!NextDataLine(in, line))
      {
        error = path + ": missing OFF counts";
        return false;
      }
      std::istringstream counts(line);
      counts >> nv >> nf >> ne;
    }
  }
  else
  {
    error = path + " is not an OFF file";
    return false;
  }
  if (nv < 0 || nf < 0 || nv > (1LL << 30) || nf > (1LL << 30))
  {
    error = path + ": invalid OFF counts";
    return false;
  }
  soup.Points.reserve(nv);
  for (long long i = 0; i < nv; ++i)
  {
    if (!NextDataLine(in, line))
    {
      error = path + ": truncated vertex list";
      return false;
    }
    std::istringstream ls(line);
    Vec3 p;
    if (!(ls >> p.x >> p.y >> p.z))
    {
      error = path + ": bad vertex line " + std::to_string(i);
      return false;
    }
    soup.Points.push_back(p);
  }
  std::vector<long long> poly;
  for (long long i = 0; i < nf; ++i)
  {
    if (!NextDataLine(in, line))
    {
      error = path + ": truncated face list";
      return false;
    }
    std::istringstream ls(line);
    long long n = 0;
    ls >> n;
    poly.assign(std::max(0LL, n), 0);
    for (long long k = 0; k < n; ++k)
    {
      if (!(ls >> poly[k]))
      {
        error = path + ": bad face line " + std::to_string(i);
        return false;
      }
    }
    AddPolygon(soup, poly);
  }
  return true;
}

bool ReadPLY(const std::string& path, TriangleSoup& soup, std::string& error)
{
  soup = TriangleSoup();
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    error = "cannot open " + path;
    return false;
  }
  std::string line;
  std::getline(in, line);
  if (line.compare(0, 3, "ply") != 0)
  {
    error = path + " is not a PLY file";
    return false;
  }
  bool binary = false;
  long long nv = 0, nf = 0;
  std::string current;
  std::vector<std::string> vertexProps; // types, with "x"/"y"/"z" positions remembered
  std::vector<std::string> vertexNames;
  std::string countType = "uchar", indexType = "int";
  while (std::getline(in, line))
  {
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "format")
    {
      std::string f;
      ls >> f;
      if (f == "binary_little_endian")
      {
        binary = true;
      }
      else if (f != "ascii")
      {
        error = path + ": unsupported PLY format " + f;
        return false;
      }
    }
    else if (word == "element")
    {
      long long n = 0;
      ls >> current >> n;
      if (current == "vertex")
      {
        nv = n;
      }
      else if (current == "face")
      {
        nf = n;
      }
    }
    else if (word == "property" && current == "vertex")
    {
      std::string type, name;
      ls >> type >> name;
      vertexProps.push_back(type);
      vertexNames.push_back(name);
    }
    else if (word == "property" && current == "face")
    {
      std::string list;
      ls >> list;
      if (list == "list")
      {
        ls >> countType >> indexType;
      }
    }
    else if (word == "end_header")
    {
      break;
    }
  }
  if (nv < 0 || nf < 0 || nv > (1LL << 30) || nf > (1LL << 30))
  {
    error = path + ": invalid PLY counts";
    return false;
  }
  auto sizeOf = [](const std::string& t) -> int {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8")
      return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16")
      return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
      return 4;
    if (t == "double" || t == "float64")
      return 8;
    return 0;
  };
  auto readBinary = [&](const std::string& t, double& value) -> bool {
    unsigned char buf[8];
    const int n = sizeOf(t);
    if (n == 0 || !in.read(reinterpret_cast<char*>(buf), n))
      return false;
    if (t == "char" || t == "int8")
      value = static_cast<std::int8_t>(buf[0]);
    else if (t == "uchar" || t == "uint8")
      value = buf[0];
    else if (t == "short" || t == "int16")
    {
      std::int16_t x;
      std::memcpy(&x, buf, 2);
      value = x;
    }
    else if (t == "ushort" || t == "uint16")
    {
      std::uint16_t x;
      std::memcpy(&x, buf, 2);
      value = x;
    }
    else if (t == "int" || t == "int32")
    {
      std::int32_t x;
      std::memcpy(&x, buf, 4);
      value = x;
    }
    else if (t == "uint" || t == "uint32")
    {
      std::uint32_t x;
      std::memcpy(&x, buf, 4);
      value = x;
    }
    else if (t == "float" || t == "float32")
    {
      float x;
      std::memcpy(&x, buf, 4);
      value = x;
    }
    else
    {
      std::memcpy(&value, buf, 8);
    }
    return true;
  };
  soup.Points.resize(nv);
  for (long long i = 0; i < nv; ++i)
  {
    double xyz[3] = { 0, 0, 0 };
    std::istringstream ls;
    if (!binary)
    {
      if (!std::getline(in, line))
      {
        error = path + ": truncated vertex list";
        return false;
      }
      ls.str(line);
    }
    for (std::size_t k = 0; k < vertexProps.size(); ++k)
    {
      double v = 0;
      const bool ok = binary ? readBinary(vertexProps[k], v) : static_cast<bool>(ls >> v);
      if (!ok)
      {
        error = path + ": bad vertex " + std::to_string(i);
        return false;
      }
      if (vertexNames[k] == "x")
        xyz[0] = v;
      else if (vertexNames[k] == "y")
        xyz[1] = v;
      else if (vertexNames[k] == "z")
        xyz[2] = v;
    }
    soup.Points[i] = Vec3(xyz[0], xyz[1], xyz[2]);
  }
  std::vector<long long> poly;
  for (long long i = 0; i < nf; ++i)
  {
    std::istringstream ls;
    if (!binary)
    {
      if (!std::getline(in, line))
      {
        error = path + ": truncated face list";
        return false;
      }
      ls.str(line);
    }
    double count = 0;
    if (!(binary ? readBinary(countType, count) : static_cast<bool>(ls >> count)) || count < 0 ||
      count > 1000)
    {
      error = path + ": bad face " + std::to_string(i);
      return false;
    }
    poly.assign(static_cast<std::size_t>(count), 0);
    for (auto& p : poly)
    {
      double v = 0;
      if (!(binary ? readBinary(indexType, v) : static_cast<bool>(ls >> v)))
      {
        error = path + ": bad face " + std::to_string(i);
        return false;
      }
      p = static_cast<long long>(v);
    }
    AddPolygon(soup, poly);
  }
  return true;
}

bool ReadMesh(const std::string& path, TriangleSoup& soup, std::string& error)
{
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == "off")
  {
    return ReadOFF(path, soup, error);
  }
  if (ext == "ply")
  {
    return ReadPLY(path, soup, error);
  }
  error = path + ": unsupported mesh format (use .off or .ply)";
  return false;
}

bool WritePLY(const std::string& path, const TriangleSoup& soup, std::string& error)
{
  std::ofstream out(path);
  if (!out)
  {
    error = "cannot write " + path;
    return false;
  }
  out << "ply\nformat ascii 1.0\ncomment generated by GeodesicShapes\n";
  out << "element vertex " << soup.Points.size() << "\nproperty double x\nproperty double y\n"
      << "property double z\nelement face " << soup.Triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  out.precision(17);
  for (const Vec3& p : soup.Points)
  {
    out << p.x << ' ' << p.y << ' ' << p.z << '\n';
  }
  for (const auto& t : soup.Triangles)
  {
    out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  }
  return static_cast<bool>(out);
}

} // namespace gs
