// The nesting of an XML file's elements, checked before VTK's XML parser reads it.
#ifndef LVDIFXmlNesting_h
#define LVDIFXmlNesting_h

#include <string>

namespace LVDIFFiles
{
/// Throws lvdif::Error(CorruptData) "<what>: XML elements nested more than <limit>
/// deep ..." when the elements of the XML file at `path` nest deeper than `limit`
/// (read a block at a time; the raw bytes after an AppendedData tag are not XML).
/// VTK's parser builds a tree of the elements that it frees recursively: a .vti of
/// 200,000 nested elements ended in a segmentation fault.
void RequireXmlNestingBelow(const std::string& path, int limit, const std::string& what);
}

#endif
