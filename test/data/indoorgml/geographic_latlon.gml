<?xml version="1.0" encoding="UTF-8"?>
<IndoorFeatures xmlns="http://www.opengis.net/indoorgml/1.0/core" xmlns:gml="http://www.opengis.net/gml/3.2" xmlns:xlink="http://www.w3.org/1999/xlink" gml:id="IF">
<primalSpaceFeatures><PrimalSpaceFeatures gml:id="PS"><cellSpaceMember><CellSpace gml:id="G1"><cellSpaceGeometry><Geometry3D>
<gml:Solid gml:id="S1" srsName="urn:ogc:def:crs:EPSG::4979" srsDimension="3"><gml:exterior><gml:Shell>
<gml:surfaceMember><gml:Polygon gml:id="G-floor"><gml:exterior><gml:LinearRing>
<gml:pos>48.0 11.0 100.0</gml:pos>
<gml:pos>48.0001 11.0 100.0</gml:pos>
<gml:pos>48.0001 11.0001 100.0</gml:pos>
<gml:pos>48.0 11.0001 100.0</gml:pos>
<gml:pos>48.0 11.0 100.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="G-ceil"><gml:exterior><gml:LinearRing>
<gml:pos>48.0 11.0 103.0</gml:pos>
<gml:pos>48.0 11.0001 103.0</gml:pos>
<gml:pos>48.0001 11.0001 103.0</gml:pos>
<gml:pos>48.0001 11.0 103.0</gml:pos>
<gml:pos>48.0 11.0 103.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="G-south"><gml:exterior><gml:LinearRing>
<gml:pos>48.0 11.0 100.0</gml:pos>
<gml:pos>48.0 11.0001 100.0</gml:pos>
<gml:pos>48.0 11.0001 103.0</gml:pos>
<gml:pos>48.0 11.0 103.0</gml:pos>
<gml:pos>48.0 11.0 100.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="G-north"><gml:exterior><gml:LinearRing>
<gml:pos>48.0001 11.0 100.0</gml:pos>
<gml:pos>48.0001 11.0 103.0</gml:pos>
<gml:pos>48.0001 11.0001 103.0</gml:pos>
<gml:pos>48.0001 11.0001 100.0</gml:pos>
<gml:pos>48.0001 11.0 100.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="G-west"><gml:exterior><gml:LinearRing>
<gml:pos>48.0 11.0 100.0</gml:pos>
<gml:pos>48.0 11.0 103.0</gml:pos>
<gml:pos>48.0001 11.0 103.0</gml:pos>
<gml:pos>48.0001 11.0 100.0</gml:pos>
<gml:pos>48.0 11.0 100.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="G-east"><gml:exterior><gml:LinearRing>
<gml:pos>48.0 11.0001 100.0</gml:pos>
<gml:pos>48.0001 11.0001 100.0</gml:pos>
<gml:pos>48.0001 11.0001 103.0</gml:pos>
<gml:pos>48.0 11.0001 103.0</gml:pos>
<gml:pos>48.0 11.0001 100.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
</gml:Shell></gml:exterior></gml:Solid>
</Geometry3D></cellSpaceGeometry></CellSpace></cellSpaceMember></PrimalSpaceFeatures></primalSpaceFeatures></IndoorFeatures>
