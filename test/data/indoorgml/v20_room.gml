<?xml version="1.0" encoding="UTF-8"?>
<core:IndoorFeatures xmlns:core="http://www.opengis.net/indoorgml/2.0/core" xmlns:gml="http://www.opengis.net/gml/3.2" xmlns:xlink="http://www.w3.org/1999/xlink" gml:id="IF">
<core:layers><core:ThematicLayer gml:id="TL"><core:primalSpace><core:PrimalSpaceLayer gml:id="PSL">
<core:cellSpaceMember><core:CellSpace gml:id="C1"><core:cellSpaceGeom><core:CellSpaceGeometry><core:geometry3D>
<gml:Solid gml:id="S1"><gml:exterior><gml:Shell>
<gml:surfaceMember><gml:Polygon gml:id="C-floor"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 0.0 0.0</gml:pos>
<gml:pos>0.0 4.0 0.0</gml:pos>
<gml:pos>5.0 4.0 0.0</gml:pos>
<gml:pos>5.0 0.0 0.0</gml:pos>
<gml:pos>0.0 0.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="C-ceil"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 0.0 3.0</gml:pos>
<gml:pos>5.0 0.0 3.0</gml:pos>
<gml:pos>5.0 4.0 3.0</gml:pos>
<gml:pos>0.0 4.0 3.0</gml:pos>
<gml:pos>0.0 0.0 3.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="C-south"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 0.0 0.0</gml:pos>
<gml:pos>5.0 0.0 0.0</gml:pos>
<gml:pos>5.0 0.0 3.0</gml:pos>
<gml:pos>0.0 0.0 3.0</gml:pos>
<gml:pos>0.0 0.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="C-north"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 4.0 0.0</gml:pos>
<gml:pos>0.0 4.0 3.0</gml:pos>
<gml:pos>5.0 4.0 3.0</gml:pos>
<gml:pos>5.0 4.0 0.0</gml:pos>
<gml:pos>0.0 4.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="C-west"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 0.0 0.0</gml:pos>
<gml:pos>0.0 0.0 3.0</gml:pos>
<gml:pos>0.0 4.0 3.0</gml:pos>
<gml:pos>0.0 4.0 0.0</gml:pos>
<gml:pos>0.0 0.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="C-east"><gml:exterior><gml:LinearRing>
<gml:pos>5.0 0.0 0.0</gml:pos>
<gml:pos>5.0 4.0 0.0</gml:pos>
<gml:pos>5.0 4.0 3.0</gml:pos>
<gml:pos>5.0 0.0 3.0</gml:pos>
<gml:pos>5.0 0.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
</gml:Shell></gml:exterior></gml:Solid>
</core:geometry3D></core:CellSpaceGeometry></core:cellSpaceGeom><core:duality xlink:href="#N1"/></core:CellSpace></core:cellSpaceMember>
</core:PrimalSpaceLayer></core:primalSpace>
<core:dualSpace><core:DualSpaceLayer gml:id="DSL">
<core:nodeMember><core:Node gml:id="N1"><core:duality xlink:href="#C1"/><core:geometry><gml:Point gml:id="NP1"><gml:pos srsDimension="3">2 2 0.5</gml:pos></gml:Point></core:geometry></core:Node></core:nodeMember>
</core:DualSpaceLayer></core:dualSpace>
</core:ThematicLayer></core:layers>
</core:IndoorFeatures>
